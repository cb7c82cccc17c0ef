// Compiled in lagfsi::solid's context by tests/fence: must NOT compile (solid -> fluid).
#include <lagfsi/fluid/fluid_model.hpp>
