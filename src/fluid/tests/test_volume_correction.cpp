// "volume_correction": "particle" (VolumeCorrection, a white-box test of the private src/fluid/volume_correction.hpp):
// each particle keeps its share of the area. What a step changes at a particle is owed to it (set_end); what a
// remesh changes is owed to the group of changed particles where it changed (owe_remesh_change), so that a
// re-triangulation of the same points (an edge flip), which moves area between neighbours, owes nothing, and the
// area of a gap the remesh closes is owed back by the particles around it. The area is conserved exactly:
// mesh + owed is the same before and after. A particle asked to give more than its share keeps a debt of its
// share and the bulk takes the rest (return_unpayable_through_bulk). "volume_correction": "source" takes the area error
// through a low-pass filter that a retried step does not advance.
#include <gtest/gtest.h>

#include "fluid_scene.hpp"

#include <vector>

namespace lagfsi::fluid {
namespace {

using fluid_test::kH;
using Scene = fluid_test::FluidScene;

TEST(ParticleVolumes, AnEdgeFlipOwesNothing) {
  // A unit square of side h, split along 0-2, then along 1-3: every particle's share changes by h^2 / 6.
  Scene s({{0, 0}, {kH, 0}, {kH, kH}, {0, kH}});
  s.mesh.tri = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<double> before = s.mesh.nodal_areas(s.cloud.x(), 4);
  s.mesh.tri = {{0, 1, 3}, {1, 2, 3}};
  const std::vector<double> after = s.mesh.nodal_areas(s.cloud.x(), 4);
  EXPECT_NEAR(after[0] - before[0], -kH * kH / 6, 1e-18);  // the flip does move the shares
  s.volume.owe_remesh_change(before, s.identity());
  for (Index i = 0; i < 4; ++i) EXPECT_NEAR(s.cloud.owed()[i], 0.0, 1e-18) << "particle " << i;
}

TEST(ParticleVolumes, AClosedGapIsOwedBackByTheParticlesAroundIt) {
  // Elements 0-1-2 and 3-4-5 of a mesh; the remesh closes the gap between them with 1-3-2 (area h^2 / 2) and
  // flips nothing else. The particles of the new element owe its area, in proportion to their gains; 0, 4
  // and 5 owe nothing.
  Scene s({{0, 0}, {kH, 0}, {0, kH}, {kH, kH}, {2 * kH, kH}, {kH, 2 * kH}});
  s.mesh.tri = {{0, 1, 2}, {3, 4, 5}};
  const std::vector<double> before = s.mesh.nodal_areas(s.cloud.x(), 6);
  const double area_before = s.mesh.area(s.cloud.x());
  s.mesh.tri = {{0, 1, 2}, {3, 4, 5}, {1, 3, 2}};
  s.volume.owe_remesh_change(before, s.identity());
  const Vec& owed = s.cloud.owed();
  for (Index i : {0, 4, 5}) EXPECT_EQ(owed[i], 0.0) << "particle " << i;
  for (Index i : {1, 2, 3}) EXPECT_NEAR(owed[i], -kH * kH / 6, 1e-18) << "particle " << i;
  EXPECT_NEAR(s.mesh.area(s.cloud.x()) + owed.sum(), area_before, 1e-18);  // conserved
}

TEST(ParticleVolumes, AMergedPairOwesTheAreaItsMergeRemoved) {
  // A strip of four elements; particles 2 and 3 (a film's two sides) are merged into 2 at their midpoint.
  // The merged particle owes the pair's two owed areas and, with its neighbours, the area the merge removed.
  Scene s({{0, 0}, {kH, 0}, {kH, 0.5 * kH}, {kH, kH}, {0, kH}, {2 * kH, 0.5 * kH}});
  s.mesh.tri = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {1, 5, 2}, {2, 5, 3}};
  s.cloud.owed() << 0, 0, 1e-7, 2e-7, 0, 0;
  const std::vector<double> before = s.mesh.nodal_areas(s.cloud.x(), 6);
  const double total_before = s.mesh.area(s.cloud.x()) + s.cloud.owed().sum();
  // The merge (what RemeshPipeline::manage_particles does): 2 takes 3's owed area and moves to (h, 0.75 h);
  // 3 goes, the others are renumbered.
  s.cloud.owed()[2] += s.cloud.owed()[3];
  s.cloud.x().segment<2>(4) = Vec2(kH, 0.75 * kH);
  s.cloud.compact({0, 0, 0, 1, 0, 0});
  s.mesh.tri = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
  s.volume.owe_remesh_change(before, {0, 1, 2, 2, 3, 4});
  EXPECT_NEAR(s.mesh.area(s.cloud.x()) + s.cloud.owed().sum(), total_before, 1e-18);
  EXPECT_GT(s.cloud.owed()[2], 3e-7);  // the removed area is owed, most by the merged particle
}

TEST(ParticleVolumes, AStepOwesEachParticleWhatItsShareLost) {
  Scene s({{0, 0}, {kH, 0}, {0, kH}, {kH, kH}});
  s.mesh.tri = {{0, 1, 3}, {0, 3, 2}};
  s.mesh.connected = {1, 1, 1, 1};
  s.volume.start(s.mesh.area(s.cloud.x()));
  s.volume.set_remeshed(s.mesh.area(s.cloud.x()), 1e-3);
  s.cloud.x()[7] = 0.9 * kH;  // particle 3 moves down: element 0-1-3 loses 0.05 h^2, 0-3-2 keeps its area
  s.volume.set_end(s.mesh.area(s.cloud.x()));
  const Vec& owed = s.cloud.owed();
  EXPECT_NEAR(owed.sum(), 0.05 * kH * kH, 1e-18);
  for (Index i : {0, 1, 3}) EXPECT_NEAR(owed[i], 0.05 * kH * kH / 3, 1e-18) << "particle " << i;
  EXPECT_NEAR(owed[2], 0.0, 1e-18);
  EXPECT_GT(s.volume.owed_rate(3), 0.0);
  EXPECT_NEAR(s.volume.water_area(), s.mesh.area(s.cloud.x()), 1e-18);  // nothing in flight
}

TEST(ParticleVolumes, AParticleAtPrescribedPressureHandsItsAreaInward) {
  // Particle 0 (p = 0 on the free surface: no continuity row) is owed 6e-7 and is in two elements, with 1, 2
  // and 2, 3: 1 and 3 get a quarter each, 2 (in both) half; particle 4, fixed too but in no element, keeps its own.
  Scene s({{0, 0}, {kH, 0}, {kH, kH}, {0, kH}, {5 * kH, 5 * kH}});
  s.mesh.tri = {{0, 1, 2}, {0, 2, 3}};
  s.cloud.owed() << 6e-7, 1e-7, 0, 0, 2e-7;
  std::vector<char> fixed(15, 0);
  fixed[3 * 0 + 2] = fixed[3 * 4 + 2] = 1;
  s.volume.hand_owed_inward(fixed);
  const Vec& owed = s.cloud.owed();
  EXPECT_EQ(owed[0], 0.0);
  EXPECT_NEAR(owed[1], 1e-7 + 1.5e-7, 1e-20);
  EXPECT_NEAR(owed[2], 3e-7, 1e-20);
  EXPECT_NEAR(owed[3], 1.5e-7, 1e-20);
  EXPECT_EQ(owed[4], 2e-7);
}

TEST(ParticleVolumes, ADebtBeyondAParticlesShareIsReturnedThroughTheBulk) {
  // A square of side 2h around an interior particle 4 (four elements; its share 4h^2/3, the corners' 2h^2/3).
  // Corner 0 is owed -3 times its share: it could not give that without turning its elements over. It keeps a
  // debt of its share; the rest goes to 4, the one particle inside. Corner 1, owed -0.5 share, keeps it.
  Scene s({{0, 0}, {2 * kH, 0}, {2 * kH, 2 * kH}, {0, 2 * kH}, {kH, kH}});
  s.mesh.tri = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  s.mesh.free = {1, 1, 1, 1, 0};
  const std::vector<double> share = s.mesh.nodal_areas(s.cloud.x(), 5);
  s.cloud.owed() << -3 * share[0], -0.5 * share[1], 0, 0, 1e-8;
  s.volume.set_remeshed(s.mesh.area(s.cloud.x()), 1e-3);  // the step's starting shares
  const double owed_before = s.cloud.owed().sum();
  s.volume.return_unpayable_through_bulk(std::vector<char>(15, 0));
  const Vec& owed = s.cloud.owed();
  EXPECT_NEAR(owed[0], -share[0], 1e-20);
  EXPECT_EQ(owed[1], -0.5 * share[1]);
  EXPECT_NEAR(owed[4], 1e-8 - 2 * share[0], 1e-20);
  EXPECT_NEAR(owed.sum(), owed_before, 1e-20);
  EXPECT_NEAR(s.volume.summary()["returned_through_bulk"].get<double>(), 2 * share[0], 1e-20);
}

TEST(SourceCorrection, TheSourceTakesTheAreaErrorThroughAFilterThatARetryDoesNotAdvance) {
  // "source", T = 0.1 s (filter time T/2 = 0.05 s): the mesh's area after remeshing jumps by e above the reference.
  // The first step of 0.01 s takes a fifth of e into the source, a retry of that step with 0.005 s a tenth (from
  // the same filter state), and once steps have gone on, the whole error: c_vol = e / (A_ref T).
  Scene s({{0, 0}, {kH, 0}, {kH, kH}, {0, kH}});
  s.mesh.tri = {{0, 1, 2}, {0, 2, 3}};
  const double a = s.mesh.area(s.cloud.x()), e = 1e-3 * a;
  s.volume.configure(VolumeCorrection::Type::source, 0.1);
  s.volume.start(a);
  s.volume.set_remeshed(a + e, 0.01);
  EXPECT_NEAR(s.volume.c_vol(), 0.2 * e / (a * 0.1), 1e-12 * e / a);
  s.volume.set_remeshed(a + e, 0.005);  // a retry with half the step
  EXPECT_NEAR(s.volume.c_vol(), 0.1 * e / (a * 0.1), 1e-12 * e / a);
  for (int k = 0; k < 400; ++k) {
    s.volume.set_remeshed(a + e, 0.01);
    s.volume.set_end(a + e);
  }
  EXPECT_NEAR(s.volume.c_vol(), e / (a * 0.1), 1e-6 * e / a);
}

}  // namespace
}  // namespace lagfsi::fluid
