#pragma once
/// @file fluid_mesh.hpp (private to src/fluid)
/// The step's mesh of the particles: its triangles (rebuilt by remeshing, remesh_pipeline.hpp, or fixed),
/// the free-surface and connected flags of the particles, and the geometric queries on it.
#include "fluid_common.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace lagfsi::fluid {

struct FluidMesh {
  std::vector<std::array<Index, 3>> tri;      // the step's elements (counter-clockwise)
  std::vector<Index> conn;                    // tri flattened (flatten(): the matrices' pattern, the output)
  std::vector<std::uint8_t> free, connected;  // per particle: on the free surface; in an element

  Index num_elements() const { return static_cast<Index>(tri.size()); }
  /// conn from tri.
  void flatten();
  /// Signed area of element e at positions x.
  double element_area(const Vec& x, Index e) const {
    const auto& t = tri[e];
    const Vec2 a = x.segment<2>(2 * t[0]), b = x.segment<2>(2 * t[1]), c = x.segment<2>(2 * t[2]);
    return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  }
  /// The mesh's area at positions x (the elements' signed areas summed in order).
  double area(const Vec& x) const;
  /// The particles' shares of the mesh's area at positions x (np of them): sum_e A_e / 3 over their elements
  /// (signed areas; zero for a particle in no element).
  std::vector<double> nodal_areas(const Vec& x, Index np) const;
  /// Flags (np of them) of the particles of the elements that have a particle i with pred(i).
  std::vector<char> in_element_with(Index np, const std::function<bool(Index)>& pred) const;
  /// Particles of an element with an interior (non-free-surface) fluid particle: the wet side of the mesh.
  std::vector<char> beside_interior_fluid(const std::vector<ParticleKind>& kind) const;
  /// The edges in one element only, as (element, k: the edge from its particle k to k + 1), in the order of
  /// their particle pairs (smaller index first): the boundary of the mesh, counter-clockwise in its element.
  /// Kept for the triangles it was found for: a step asks for it three times (the free surface's flags, the
  /// Robin edges, the next remesh's boundary chains) on the same triangles, and each search sorts every edge.
  const std::vector<std::pair<Index, int>>& boundary_edges() const;
  /// Per element, its edges on the free surface (bit k: from its particle k to k + 1): in no other element,
  /// between two free-surface fluid particles (the Robin free-surface pressure, fluid_element.hpp).
  std::vector<unsigned char> free_surface_edges(const std::vector<ParticleKind>& kind) const;
  /// Checkpoints (state_archive.hpp; fluid_checkpoint.cpp).
  void serialize(StateArchive& ar);

 private:
  std::vector<std::pair<Index, int>> find_boundary_edges() const;
  // boundary_edges() of the triangles boundary_of_ (compared whole: any change of tri, wherever it is made,
  // finds the boundary again; no triangles, no boundary).
  mutable std::vector<std::array<Index, 3>> boundary_of_;
  mutable std::vector<std::pair<Index, int>> boundary_;
};

}  // namespace lagfsi::fluid
