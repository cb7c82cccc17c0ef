// Compiled in lagfsi::meshing's context by tests/fence: must NOT compile (meshing -> core).
#include <lagfsi/model.hpp>
