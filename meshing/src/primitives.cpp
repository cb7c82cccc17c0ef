// Placeholder until the meshing module lands (being written now).
#include <lagfsi/meshing/primitives.hpp>
