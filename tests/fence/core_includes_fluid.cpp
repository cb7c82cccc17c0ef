// Compiled in lagfsi::core's context by tests/fence: must NOT compile (core -> fluid is upward).
#include <lagfsi/fluid/fluid_model.hpp>
