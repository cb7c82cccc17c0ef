// The particles of a fluid region ("particles": "structured" or "unstructured"): both layouts give the spacing h
// its meaning, a particle per h^2 of water, so that a case's h says how fine it is whichever layout it takes, and
// the particles an inflow injects (layers h apart on lanes h apart) are as dense as those the region started with.
#include <gtest/gtest.h>

#include <string>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;

/// The particles of a 1 x 0.5 m rectangle of spacing 0.02 m laid out as `layout`, one step after the start.
double particles_of(const std::string& layout) {
  const std::string text = R"({
    "name": "region_)" + layout +
                           R"(",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 1e-3},
    "gravity": [0.0, 0.0],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.02,
      "particles": ")" + layout +
                           R"(",
      "regions": [{"type": "rectangle", "origin": [0, 0], "size": [1.0, 0.5]}],
      "scheme": {"type": "fractional_step"}
    }],
    "output": {"every": 1}
  })";
  const RunResult r = run_case_text(fresh_dir("region_" + layout), text);
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  if (r.exit_code != 0) return 0.0;
  return read_csv(r.out_dir / "log.csv")["nodes"].front();
}

TEST(FluidRegions, UnstructuredParticlesAreAsDenseAsALatticeOfTheSameSpacing) {
  // A Delaunay mesh whose longest edge is h has mostly shorter edges: its nodes were 2.37 times the lattice's here
  // (1.09 times since its bound is 1.5 h).
  const double lattice = particles_of("structured"), mesh = particles_of("unstructured");
  ASSERT_GT(lattice, 1000.0);  // 51 x 26 points
  EXPECT_GT(mesh, 0.8 * lattice) << "lattice " << lattice << ", unstructured " << mesh;
  EXPECT_LT(mesh, 1.25 * lattice) << "lattice " << lattice << ", unstructured " << mesh;
}

}  // namespace
