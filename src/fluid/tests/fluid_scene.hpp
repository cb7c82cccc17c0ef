#pragma once
/// @file fluid_scene.hpp
/// A hand-made PFEM fluid for the white-box tests of src/fluid (test_volume_correction.cpp,
/// test_particle_management.cpp): fluid particles at the given positions, spacing kH, the mesh of the given
/// triangles, and the particle volumes' bookkeeping ("volume_correction": "particle", T = 0.01 s).
#include "fluid_mesh.hpp"
#include "volume_correction.hpp"

#include <array>
#include <vector>

namespace lagfsi::fluid::fluid_test {

constexpr double kH = 0.01;

struct FluidScene {
  FluidConstants c;
  ParticleCloud cloud;
  FluidMesh mesh;
  VolumeCorrection volume{c, cloud, mesh};
  explicit FluidScene(const std::vector<Vec2>& pts, const std::vector<std::array<Index, 3>>& tri = {}) {
    c.h = kH;
    c.name = "water";
    cloud.assign(pts, std::vector<ParticleKind>(pts.size(), ParticleKind::Fluid), kH);
    mesh.tri = tri;
    volume.configure(VolumeCorrection::Type::particle, 0.01);
  }
  /// present[i] = i: every particle is still there, numbered as before (VolumeCorrection::owe_remesh_change).
  std::vector<Index> identity() const {
    std::vector<Index> k(static_cast<size_t>(cloud.n()));
    for (Index i = 0; i < cloud.n(); ++i) k[static_cast<size_t>(i)] = i;
    return k;
  }
};

}  // namespace lagfsi::fluid::fluid_test
