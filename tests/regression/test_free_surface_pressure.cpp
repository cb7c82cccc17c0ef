// The free-surface pressure condition of the monolithic scheme, the particles' own volumes, and the area a splash
// keeps (docs/decisions/0004-robin-free-surface-pressure.md, 0005-particle-volumes.md).
// With p = 0 prescribed ("dirichlet", the alpha shape's default), the free-surface particles have no continuity row,
// and in a splash, where most particles lie on a surface, the steps lose area (cases/studies/conservation: 4-17 % of
// the dam break's area by 1 s in every domain detection but the level set's). The Robin condition ("robin",
// fluid_element.hpp) keeps the continuity there and pulls the pressure weakly to the traction-free value.
//  - A coarse dam break (L/10, 0.8 s, advected domain, no-slip walls as constraints, no volume correction):
//    measured largest area drift 5.64 % with "dirichlet" (+0.55 % changed in the steps) and 1.21 % with "robin"
//    (-0.45 %); with "dirichlet" +1.73 % in the steps before water against a wall was kept (decision 0020: the
//    surfaces the separation test opened along the walls had no continuity row either); 5.64 % (+1.39 %) and
//    1.22 % (-0.39 %) before the merge of two surfaces that meet, 5.81 % (-2.01 %) and 0.85 % (-0.17 %) before the
//    long side of a corner's triangle was marked a free surface.
//  - "volume_correction": "particle" (volume_correction.hpp) with "robin": each particle keeps its share of the
//    area; the water is the mesh's area plus what the particles in flight carry. The same coarse dam break:
//    measured largest drift of the water 0.30 % and of the mesh 1.31 % (1.28 % of the area is in flight at the
//    end), and the mesh's area + the owed areas + what left the domain equal the initial area to round-off.
//  - All under Newmark's trapezoidal rule, with which they were measured and which compares the surface
//    conditions alone (a Robin fluid's default integrator is generalized-alpha). With generalized-alpha the water's
//    largest drift with the walls as constraints is within the same bound; with wall particles it was 5.4 % at
//    rho_inf = 0.8 (166 wall crossings put back), 1.7 / 3.5 / 2.5 % at 0.9 / 1 / 0.6, against 1.3 % under
//    Newmark (26): at this resolution (L/10, 2 ms) wall particles let water through in a splash, more so under
//    generalized-alpha; at L/20 too (dam_break_tank: 1.68 % against 0.63 %), so wall particles with a Robin
//    surface now default to Newmark (fluid_preferred_integrator).
//  - Still water stays still with "robin": StillWater.RobinFreeSurfaceStaysStill (the hydrostatic state with
//    p = 0 on the surface is a solution of the element: PspgElement.RobinTermVanishesAtRestWithTheSurfaceAtZero-
//    Pressure).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;

/// `scheme`: the scheme's keys (JSON members).
std::string coarse_dam_break(const std::string& scheme, const std::string& wall_model = "constraints") {
  return R"({
    "name": "dam_break_coarse",
    "analysis": {"type": "dynamic", "dt": 2e-3, "end_time": 0.8, "integrator": {"type": "newmark"}},
    "gravity": [0.0, -9.81],
    "bodies": [{
      "name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.0146,
      "domain_detection": "advected", "wall_friction": "held", "wall_model": ")" +
         wall_model + R"(",
      "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.146, 0.292]}],
      "walls": [{"name": "tank", "points": [[0, 0.584], [0, 0], [0.584, 0], [0.584, 0.584]]}],
      "initial_pressure": {"type": "hydrostatic", "level": 0.292},
      "scheme": {)" +
         scheme + R"(}
    }],
    "probes": [{"name": "area", "type": "fluid_area", "body": "water"},
               {"name": "water", "type": "water_area", "body": "water"}],
    "output": {"every": 100000, "vtk": false}
  })";
}

/// Largest |area / initial - 1| of a run's probes, and its summary's change in the steps over the initial area.
std::pair<double, double> area_drift(const std::string& free_surface_pressure) {
  const RunResult r = run_case_text(
      fresh_dir("dam_break_coarse_" + free_surface_pressure),
      coarse_dam_break(R"("volume_correction": "none", "free_surface_pressure": ")" + free_surface_pressure + "\""));
  EXPECT_EQ(r.exit_code, 0) << free_surface_pressure << ": " << r.stderr_text;
  const Csv c = probes_of(r);
  double drift = 0;
  for (double a : c["area"]) drift = std::max(drift, std::abs(a / c["area"][0] - 1));
  const auto s = summary_of(r);
  const auto& area = s["bodies"][0]["fluid_area"];
  const double steps = area["change_in_steps"].get<double>() / area["initial"].get<double>();
  std::printf("%s: largest area drift %.2f %%, change in the steps %+.2f %%\n", free_surface_pressure.c_str(),
              100 * drift, 100 * steps);
  return {drift, steps};
}

TEST(FreeSurfacePressure, RobinConditionKeepsTheSplashArea) {
  const auto [drift_d, steps_d] = area_drift("dirichlet");
  const auto [drift_r, steps_r] = area_drift("robin");
  EXPECT_LT(drift_r, 0.02);
  EXPECT_LT(drift_r, 0.5 * drift_d);
  EXPECT_LT(std::abs(steps_r), 0.01);
  EXPECT_LT(std::abs(steps_d), 0.05);
}

/// The coarse dam break with particle volumes and the Robin condition: its largest drifts (water, mesh), and what
/// its summary's balance, mesh + owed + left - initial, leaves, over the initial area.
struct Water {
  double water = 0, mesh = 0, balance = 1, in_flight = 0;
};
Water particle_volumes(const std::string& wall_model) {
  const RunResult r =
      run_case_text(fresh_dir("dam_break_coarse_particle_" + wall_model),
                    coarse_dam_break(R"("free_surface_pressure": "robin", )"
                                     R"("volume_correction": "particle", "volume_relaxation_time": 0.02)",
                                     wall_model));
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  Water w;
  if (r.exit_code != 0) return w;
  const Csv c = probes_of(r);
  for (size_t k = 0; k < c["area"].size(); ++k) {
    w.mesh = std::max(w.mesh, std::abs(c["area"][k] / c["area"][0] - 1));
    w.water = std::max(w.water, std::abs(c["water"][k] / c["water"][0] - 1));
  }
  const auto s = summary_of(r);
  const auto& area = s["bodies"][0]["fluid_area"];
  const double initial = area["initial"].get<double>();
  const double balance = area["final"].get<double>() + area["owed_by_particles"].get<double>() +
                         area["left_domain"].get<double>() - initial;
  w.balance = balance / initial;
  w.in_flight = area["in_flight"].get<double>() / initial;
  std::printf("%s: largest drift: water %.2f %%, mesh %.2f %%; in flight %.2f %%; balance %.1e\n", wall_model.c_str(),
              100 * w.water, 100 * w.mesh, 100 * w.in_flight, w.balance);
  return w;
}

TEST(ParticleVolumes, TheSplashKeepsItsWaterInTheParticles) {
  const Water w = particle_volumes("constraints");
  EXPECT_LT(std::abs(w.balance), 1e-10);  // every particle's area is accounted for
  EXPECT_LT(w.water, 0.01);
  // The drops in flight carry their water: at the end they hold more of it than the water drifts at most
  // (measured: 1.28 % in flight, the water's largest drift 0.30 %, the mesh's 1.31 %; 0.85 %, 0.53 % and 0.88 %
  // before the merge of two surfaces that meet, 0.93 %, 0.59 % and 1.27 % before the long side of a corner's
  // triangle was marked a free surface).
  EXPECT_GT(w.in_flight, w.water);
  EXPECT_LT(w.water, w.mesh);
}

TEST(ParticleVolumes, AFluidParticleRemovedAtAWallParticleLeavesItsAreaToIt) {
  // With wall particles, a fluid particle pressed against one is removed (the wall stands for it): its share
  // and what it was owed go to the wall particle, which hands them to the fluid. Before, they were lost: the
  // L/20 dam break's balance missed 13.6 % of the area by 1 s.
  const Water w = particle_volumes("particles");
  EXPECT_LT(std::abs(w.balance), 1e-10);
  EXPECT_LT(w.water, 0.02);
}

}  // namespace
