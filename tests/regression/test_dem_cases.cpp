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
      {"name": "gravity", "type": "energy", "body": "bed", "kind": "gravity"},
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
      // the bed fell onto the floor; the energy balance closes within 1 % of the potential energy released
      const double released = c["gravity"].front() - c["gravity"].back();
      std::printf("contacts %g, released %g J, dissipated %g J, balance %g J\n", c["contacts"].back(), released,
                  c["dissipated"].back(), c["balance"].back());
      EXPECT_GT(c["contacts"].back(), 200);
      EXPECT_GT(c["dissipated"].back(), 0);
      EXPECT_GT(released, 0);
      EXPECT_LT(std::abs(c["balance"].back()), 0.01 * released);
      EXPECT_TRUE(fs::exists(r.out_dir / "bed.pvd"));
    }
  }
  EXPECT_GT(probes[0].size(), 1000u);
  EXPECT_EQ(probes[0], probes[1]) << "two runs on 1 thread differ";
  EXPECT_EQ(probes[0], probes[2]) << "1 and 2 threads differ (the sweep sums each disc's pairs in a fixed order)";
}

/// A floor moving up at 0.1 m/s (a wall with a velocity) hits a disc at rest, elastically: the disc leaves at
/// 0.2 m/s (the wall's mass is infinite), and the wall's .vtp series follows the wall.
TEST(DemCases, MovingWallPushesADisc) {
  const fs::path dir = fresh_dir("dem_moving_wall");
  const RunResult r = run_case_text(dir, R"({
    "name": "dem_moving_wall",
    "analysis": {"type": "dynamic", "dt": 1e-4, "end_time": 0.02},
    "bodies": [{
      "name": "disc", "type": "dem", "material": {"density": 2500},
      "contact": {"law": "linear", "kn": 1e6, "damping": "restitution", "restitution": 1.0},
      "discs": [{"type": "list", "discs": [[0.0, 0.0105, 0.01]]}],
      "walls": [{"name": "piston", "points": [[-0.05, 0.0], [0.05, 0.0]], "velocity": [0.0, 0.1],
                 "function": {"type": "ramp", "t0": 0.0, "t1": 1e-9}}],
      "time_step": {"dt": 1e-6}
    }],
    "probes": [{"name": "vy", "type": "disc", "body": "disc", "id": 0, "quantity": "vy"}],
    "output": {"every": 50}
  })",
                                    "--quiet --threads 1");
  const Csv c = probes_of(r);
  ASSERT_GT(c.rows(), 10u);
  std::printf("disc speed after the hit %.6f m/s\n", c["vy"].back());
  EXPECT_NEAR(c["vy"].back(), 0.2, 0.002);
  EXPECT_TRUE(fs::exists(r.out_dir / "disc_walls.pvd"));
}

/// The same floor starting 2 cm below the disc, beyond the neighbour skin (0.5 r = 5 mm): the lists must be rebuilt
/// when the wall has moved more than the skin since the last build (DemBody::needs_rebuild measures the wall's
/// travel from the current time), or the floor passes through the disc.
TEST(DemCases, MovingWallReachesADiscBeyondTheSkin) {
  const fs::path dir = fresh_dir("dem_moving_wall_far");
  const RunResult r = run_case_text(dir, R"({
    "name": "dem_moving_wall_far",
    "analysis": {"type": "dynamic", "dt": 1e-3, "end_time": 0.3},
    "bodies": [{
      "name": "disc", "type": "dem", "material": {"density": 2500},
      "contact": {"law": "linear", "kn": 1e6, "damping": "restitution", "restitution": 1.0},
      "discs": [{"type": "list", "discs": [[0.0, 0.03, 0.01]]}],
      "walls": [{"name": "piston", "points": [[-0.05, 0.0], [0.05, 0.0]], "velocity": [0.0, 0.1]}],
      "time_step": {"dt": 1e-5}
    }],
    "probes": [{"name": "vy", "type": "disc", "body": "disc", "id": 0, "quantity": "vy"}],
    "output": {"every": 100}
  })",
                                    "--quiet --threads 1");
  const Csv c = probes_of(r);
  ASSERT_GT(c.rows(), 10u);
  EXPECT_NEAR(c["vy"].back(), 0.2, 0.002);
}

/// cases/dem_column_collapse at half size (a 0.1 m column of discs r 1.5-2 mm, 0.5 s): the column collapses and
/// comes to rest with a run-out in the band of the scalings and of the full case.
TEST(DemCases, ColumnCollapseCi) {
  const auto r = run_case_1thread("cases/dem_column_collapse/case.json", "dem_column_collapse_ci",
                                  {"bodies.0.discs.0.region.size=[0.1,0.085]", "bodies.0.discs.0.radius=[0.0015,0.002]",
                                   "bodies.0.walls.1.points=[[0.1,0],[0.1,0.4]]", "bodies.0.settle.time=0.2",
                                   "analysis.end_time=0.6", "bodies.0.discs_csv=false", "output.every=1000"});
  const Csv c = probes_of(r);
  ASSERT_GT(c.rows(), 10u);
  const double l0 = 0.1, h0 = c["height_wall"].front(), front = c["runout"].back();
  double ke_max = 0;
  for (double k : c["kinetic"]) ke_max = std::max(ke_max, k);
  const double runout = (front - l0) / l0, a = h0 / l0;
  std::printf("a = %.3f, (L - L0)/L0 = %.3f (1.2a %.3f, 1.8a %.3f), final KE / peak %.2e\n", a, runout, 1.2 * a,
              1.8 * a, c["kinetic"].back() / ke_max);
  EXPECT_GT(a, 0.4);
  EXPECT_LT(a, 0.6);
  EXPECT_GT(runout, 0.5 * 1.2 * a);  // it collapsed, and not much less than the scalings say
  EXPECT_LT(runout, 2.5 * 1.8 * a);  // nor runs away (the full case: 1.29 x 1.8a)
  EXPECT_LE(c["height_wall"].back(), h0 + 1e-3);
  EXPECT_LT(c["kinetic"].back(), 0.05 * ke_max);
}

/// cases/dem_blast_crater reduced to a bed 0.3 m x 0.15 m (3200 discs), dt 1e-6 s, 3 ms: the blast loads the
/// surface, the kinetic energy peaks first at 0.05 m then at 0.10 m depth, discs are marked ruptured and a
/// crater forms under the charge.
TEST(DemCases, BlastCraterCi) {
  const auto r = run_case_1thread(
      "cases/dem_blast_crater/case.json", "dem_blast_crater_ci",
      {"bodies.0.discs.0.region.size=[0.3,0.15]", "bodies.0.walls.0.points=[[0,0.25],[0,0],[0.3,0],[0.3,0.25]]",
       "bodies.0.blast.position=[0.15,0.6495]", "bodies.0.time_step.dt=1e-6", "bodies.0.blast.exposure_every=10",
       "bodies.0.crater.offsets=[-0.02,0,0.02]", "bodies.0.discs_csv=false", "analysis.end_time=0.003",
       "probes.0.at=[0.15,0.0995]", "probes.1.at=[0.15,0.0495]", "probes.2.at=[0.15,0.0295]",
       "probes.3.at=[0.15,0.0095]", "output.every=100"});
  const Csv c = probes_of(r);
  ASSERT_GT(c.rows(), 100u);
  const auto s = summary_of(r);
  auto peak_time = [&](const std::string& col) {
    size_t best = 0;
    for (size_t i = 0; i < c.rows(); ++i)
      if (c[col][i] > c[col][best]) best = i;
    return c["time"][best];
  };
  const double t5 = peak_time("ke_005"), t10 = peak_time("ke_010");
  std::ifstream crater(r.out_dir / "crater.csv");
  std::string line1, line2;
  std::getline(crater, line1);
  std::getline(crater, line2);
  const double depth = std::stod(line2.substr(line2.find("depth = ") + 8));
  std::printf("blast work %.4g J, KE peaks at 0.05 m %.3f ms, 0.10 m %.3f ms, marked %d, crater depth %.4f m\n",
              c["blast_work"].back(), 1e3 * t5, 1e3 * t10, s["bodies"][0]["marked_discs"].get<int>(), depth);
  EXPECT_GT(c["blast_work"].back(), 0.0);
  EXPECT_GT(t5, 0.3e-3);  // after the shock's arrival (0.38 ms at 0.5 m)
  EXPECT_GT(t10, t5);     // the wave travels down
  EXPECT_GT(s["bodies"][0]["marked_discs"].get<int>(), 0);
  EXPECT_GT(depth, 0.0);
  EXPECT_LT(depth, 0.1);
}

}  // namespace
