// The conservative remesh's particle management (RemeshPipeline::remesh_step with "domain_detection":
// "advected", a white-box test of the private src/fluid/remesh_pipeline.hpp) on hand-made meshes, with
// "volume_correction": "particle", whose bookkeeping (mesh + owed + left the domain = the initial area) must
// hold through every remesh:
//  - three particles put on one wall corner in one step (FluidWalls::snap_to_walls lands a particle leaving
//    through a corner on the corner) become one. The first pair was merged and the third was left on the
//    survivor: the triangulation then failed on the duplicate point (cases/dam_break_obstacle with the
//    advected domain, walls as constraints: twelve failed remeshes at the obstacle's corners in 1 s);
//  - a remesh that fails after the management changed the cloud has owed what the management changed. The
//    step is retried from the managed cloud and mesh, which were not owed before (the same run lost 2.8 % of
//    its water from the bookkeeping in four such failures).
#include <gtest/gtest.h>

#include "fluid_energy.hpp"
#include "fluid_scene.hpp"
#include "fluid_walls.hpp"
#include "ghosts.hpp"
#include "remesh_pipeline.hpp"

#include <vector>

namespace lagfsi::fluid {
namespace {

using fluid_test::kH;

/// The scene with the remeshing's pieces, advected detection.
struct Scene : fluid_test::FluidScene {
  Ghosts ghosts;
  FluidWalls walls;
  FluidEnergy energy{c, cloud, mesh, walls};
  RemeshPipeline remesh{c, cloud, mesh, ghosts};
  Scene(const std::vector<Vec2>& pts, const std::vector<std::array<Index, 3>>& tri) : FluidScene(pts, tri) {
    volume.start(mesh.area(cloud.x()));
    RemeshPipeline::Settings s;
    s.detection = meshing::DomainDetection::Advected;
    remesh.configure(s);
  }
  /// The bookkeeping's total: the mesh's area and what the particles are owed (none left the domain here).
  double water() const { return mesh.area(cloud.x()) + cloud.owed().sum(); }
};

TEST(ParticleManagement, ThreeParticlesPutOnOneCornerBecomeOne) {
  // A square of side h in the corner of a floor and a wall, two elements: 0-3-4 and 1-4-5, where 0 and 1 were
  // put on the corner at the end of the step, and 2, a drop in no element, too.
  Scene s({{0, 0}, {0, 0}, {0, 0}, {kH, 0}, {kH, kH}, {0, kH}}, {{0, 3, 4}, {1, 4, 5}});
  s.cloud.owed() << 1e-7, 2e-7, 3e-7, 0, 0, 0;
  const double before = s.water();
  const std::vector<char> on_wall = {2, 2, 2, 1, 0, 1};  // constrained components: the corner's two
  ASSERT_NO_THROW(s.remesh.remesh_step(0.001, s.volume, s.energy, on_wall));
  ASSERT_EQ(s.cloud.n(), 4) << "one particle is left on the corner";
  EXPECT_EQ(s.cloud.pos(0), Vec2(0, 0));
  EXPECT_NEAR(s.mesh.area(s.cloud.x()), kH * kH, 1e-18) << "the square";
  EXPECT_NEAR(s.water(), before, 1e-18) << "what the three were owed is the survivor's";
}

TEST(ParticleManagement, ARemeshThatFailsHasOwedWhatTheManagementChanged) {
  // A strip of five elements where 2 and 3 (0.1 h apart) are merged, which removes area; and a drop of two
  // particles on top of each other (6, 7: in no element, no wall), on which the triangulation fails.
  Scene s({{0, 0},
           {kH, 0},
           {kH, 0.5 * kH},
           {kH, 0.6 * kH},
           {0, kH},
           {2 * kH, 0.5 * kH},
           {5 * kH, 5 * kH},
           {5 * kH, 5 * kH}},
          {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {1, 5, 2}, {2, 5, 3}});
  const double before = s.water();
  EXPECT_THROW(s.remesh.remesh_step(0.001, s.volume, s.energy), SolverError);
  EXPECT_EQ(s.cloud.n(), 7) << "the pair was merged before the triangulation failed";
  EXPECT_NEAR(s.water(), before, 1e-18) << "the merge's change is owed";
}

}  // namespace
}  // namespace lagfsi::fluid
