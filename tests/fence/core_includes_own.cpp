// Compiled in lagfsi::core's context by tests/fence: must compile (the control of the probes).
#include <lagfsi/meshing/remesh.hpp>
#include <lagfsi/model.hpp>
#include <lagfsi/types.hpp>
