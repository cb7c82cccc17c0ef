#pragma once
/// @file remesh_scene.hpp
/// A hand-made PFEM fluid with the remeshing's pieces (RemeshPipeline with the advected domain detection), for the
/// white-box tests of the particle management (test_particle_management.cpp, test_divided_management.cpp).
#include "fluid_boundaries.hpp"
#include "fluid_energy.hpp"
#include "fluid_scene.hpp"
#include "ghosts.hpp"
#include "remesh_pipeline.hpp"

#include <array>
#include <vector>

namespace lagfsi::fluid::fluid_test {

/// The scene with the remeshing's pieces, advected detection.
struct RemeshScene : FluidScene {
  Ghosts ghosts;
  FluidBoundaries boundaries;
  FluidEnergy energy{c, cloud, mesh, boundaries};
  RemeshPipeline remesh{c, cloud, mesh, ghosts};
  RemeshScene(const std::vector<Vec2>& pts, const std::vector<std::array<Index, 3>>& tri) : FluidScene(pts, tri) {
    volume.start(mesh.area(cloud.x()));
    RemeshPipeline::Settings s;
    s.detection = meshing::DomainDetection::Advected;
    remesh.configure(s);
  }
  /// The bookkeeping's total: the mesh's area and what the particles are owed (none left the domain here).
  double water() const { return mesh.area(cloud.x()) + cloud.owed().sum(); }
};

}  // namespace lagfsi::fluid::fluid_test
