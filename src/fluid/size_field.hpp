#pragma once
/// @file size_field.hpp (private to src/fluid)
/// The particle size field h(x, t) of an adaptive fluid ("size_field", fluid_input.cpp): fine where the flow
/// needs it, coarse in the calm bulk.
///
/// Sizing: the finest size h_min (the body's "spacing") at the features, growing linearly with the distance d
/// to the nearest one, h = min(h_max, h_min + g d), g the gradation (the size grows by about g per layer of
/// particles: with g = 0.25 the next layer's particles are 25 % larger); refinement boxes impose their own
/// size s inside them (within their time window) and grade from it outside, s + g d_box. The features are the
/// free surface, the walls and the structures' wet faces (their wall and ghost particles) and the open
/// boundaries: every particle on the boundary of the fluid's mesh or joined to a wall or ghost particle; and,
/// when a threshold is set, the particles where the flow strains fast: the strain rate of the P1 velocity,
/// gamma = sqrt(2 D:D) with D = (grad v + grad v^T) / 2 (the shear rate of a simple shear; zero in a rigid motion),
/// averaged over a particle's elements by area, at or above the threshold (a flow indicator in the spirit of the
/// velocity-gradient error indicators of adaptive finite elements, Zienkiewicz & Zhu, IJNME 24:337, 1987). The
/// same rule sizes the initial particles (the regions meshed graded, d the distance to the region's outline)
/// and, at every remesh, the particles' target sizes on the mesh: a multi-source Dijkstra over the mesh's
/// edges that carries each particle's nearest source and measures the straight distance to it, so that the
/// size is h_min + g |x - x_source| for the source that gives the smallest size (a distance transform on a
/// graph; the size is then g-Lipschitz along every path, the gradation limit of Frey & George, "Mesh
/// Generation", 2008, ch. 20, and of the PFEM adaptivity of Falla et al., Comput. Part. Mech. 2023, and
/// Leyssens, Lambrechts & Remacle, arXiv:2512.20347, 2025).
#include <lagfsi/params.hpp>
#include <lagfsi/types.hpp>

#include <array>
#include <functional>
#include <vector>

namespace lagfsi::fluid {

class SizeField {
 public:
  /// A refinement box: size `size` inside [lo, hi] from time `from` to time `to`.
  struct Box {
    Vec2 lo, hi;
    double size = 0, from = 0, to = 0;
  };

  /// "size_field": "uniform" or "adaptive" becomes {"type": ...} (before the body's keys are validated).
  static void expand_shorthand(Json& body);
  /// Reads "size_field" of a fluid body of finest size h ("uniform", "adaptive" or an object; see the key
  /// tables in size_field.cpp).
  void read(Params body, double h);

  bool adaptive() const { return adaptive_; }
  double h_min() const { return h_min_; }
  double h_max() const { return h_max_; }
  double gradation() const { return gradation_; }
  const std::vector<Box>& boxes() const { return boxes_; }
  /// The strain rate (1/s) at or above which a particle is a feature (0: no flow indicator).
  double strain_rate() const { return strain_rate_; }

  /// Marks as sources the particles whose strain rate (area-weighted over their elements `tri` of the points `pts`
  /// with velocities `v`) is at or above strain_rate(); returns how many it marked. Nothing without a threshold.
  Index mark_straining(const std::vector<Vec2>& pts, const std::vector<Vec2>& v,
                       const std::vector<std::array<Index, 3>>& tri, std::vector<char>& source) const;

  /// The size at x, at distance d from the nearest feature, at time t (the refinement boxes active then).
  double at(const Vec2& x, double d, double t) const;
  /// The initial size in a region whose outline is `loops` (its free surface and walls): at(x, d, 0) with d the
  /// distance from the outline.
  std::function<double(const Vec2&)> initial_size(std::vector<std::vector<Vec2>> loops) const;
  /// The size bound to give the mesher (meshing::mesh_polygon) for particles of size `size`: it bounds an element's
  /// longest edge, and the edges are then mostly shorter (median about 0.7 of the bound), so kMesherScale times the
  /// size, which gives edges about the size, where the management's coarsening leaves them.
  std::function<double(const Vec2&)> mesher_size(std::function<double(const Vec2&)> size) const;
  /// The mesher's bound for a uniform unstructured region of spacing h_min: 1.5 h_min, which gives about the
  /// particles of a lattice of spacing h_min, the density an inflow injects (a bound of h_min gives more than twice
  /// as many). Larger than mesher_size's scale: no management coarsens a uniform region towards its size.
  std::function<double(const Vec2&)> uniform_mesher_size() const;

  /// The target sizes h[i] of the particles at `pts` on the mesh `tri`: `source[i]` marks the features'
  /// particles (size h_min, or a box's where it is smaller); a particle no element uses is a source too.
  void targets(const std::vector<Vec2>& pts, const std::vector<std::array<Index, 3>>& tri,
               const std::vector<char>& source, double t, std::vector<double>& h) const;

 private:
  /// The smallest size the boxes active at t give at x (graded outside them), h_max when none.
  double box_size(const Vec2& x, double t) const;
  bool adaptive_ = false;
  double h_min_ = 0, h_max_ = 0, gradation_ = 0.25, strain_rate_ = 0;
  std::vector<Box> boxes_;
};

}  // namespace lagfsi::fluid
