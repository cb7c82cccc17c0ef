// Regression of the DEM body at CI size (seconds): determinism of the parallel force sweep (the same probes to
// the last bit for a given thread count, and in fact for 1 and 2 threads), the granular column collapse and the
// blast crater at reduced size.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "fluid_checks.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A bed of about 1800 polydisperse discs falling into a box, friction and rotation on.
json settling_bed() {
  return json::parse(R"({
    "name": "dem_settling",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 0.05},
    "gravity": [0, -9.81],
    "bodies": [{
      "name": "bed", "type": "dem",
      "material": {"density": 2500},
      "contact": {"law": "linear", "kn": 1e5, "damping": "restitution", "restitution": 0.5, "friction": 0.5,
                  "tangential_damping_ratio": 0.1},
      "discs": [{"type": "random", "region": {"type": "rectangle", "origin": [0, 0], "size": [0.2, 0.15]},
                 "radius": [0.0015, 0.0025], "fraction": 0.5, "seed": 3}],
      "walls": [{"name": "box", "points": [[0, 0.3], [0, 0], [0.2, 0], [0.2, 0.3]]}],
      "time_step": {"dt": 2e-5}
    }],
    "probes": [
      {"name": "ke", "type": "energy", "body": "bed", "kind": "kinetic"},
      {"name": "elastic", "type": "energy", "body": "bed", "kind": "elastic"},
      {"name": "dissipated", "type": "energy", "body": "bed", "kind": "dissipated"},
      {"name": "balance", "type": "energy", "body": "bed", "kind": "balance"},
      {"name": "contacts", "type": "contacts", "body": "bed"},
      {"name": "y0", "type": "disc", "body": "bed", "id": 0, "quantity": "y"},
      {"name": "w0", "type": "disc", "body": "bed", "id": 0, "quantity": "omega"}
    ],
    "output": {"every": 25}
  })");
}

TEST(DemCases, ParallelSweepIsDeterministic) {
  std::string probes[3];
  const char* threads[3] = {"1", "1", "2"};
  for (int k = 0; k < 3; ++k) {
    const fs::path dir = fresh_dir("dem_determinism_" + std::to_string(k));
    const RunResult r = run_case_text(dir, settling_bed().dump(2), std::string("--quiet --threads ") + threads[k]);
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    probes[k] = slurp(r.out_dir / "probes.csv");
    if (k == 0) {
      const Csv c = read_csv(r.out_dir / "probes.csv");
      // the bed fell and is in contact; the energy balance closes within 2 % of the energy dissipated
      EXPECT_GT(c["contacts"].back(), 1000);
      EXPECT_GT(c["dissipated"].back(), 0);
      EXPECT_LT(std::abs(c["balance"].back()), 0.02 * c["dissipated"].back());
      EXPECT_TRUE(fs::exists(r.out_dir / "bed.pvd"));
    }
  }
  EXPECT_GT(probes[0].size(), 1000u);
  EXPECT_EQ(probes[0], probes[1]) << "two runs on 1 thread differ";
  EXPECT_EQ(probes[0], probes[2]) << "1 and 2 threads differ (the sweep sums each disc's pairs in a fixed order)";
}

}  // namespace
