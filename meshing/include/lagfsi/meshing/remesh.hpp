#pragma once
/// @file remesh.hpp
/// PFEM remeshing of a particle cloud (Idelsohn, Oñate & Del Pin 2004; Avancini 2018, sec. 6.7):
/// Delaunay triangulation of all particles, the alpha-shape test, removal of elements made only of
/// wall particles, free-surface detection, and the geometric part of particle-quality control.
///
/// The alpha test is a single comparison per element, done here on the triangulation itself: an element
/// is deleted when its circumradius R exceeds alpha * h_e, with h_e the mean of its three particles'
/// spacings h_i. CGAL's Alpha_shape_2 class is deliberately not used (it builds a full filtration and was
/// measured 6-20x slower than the triangulation itself).
///
/// CGAL types do not appear here; see meshing/src/remesh.cpp.
#include <lagfsi/meshing/previous_domain.hpp>
#include <lagfsi/types.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace lagfsi::meshing {

/// What a particle is. Walls and ghosts are boundary particles whose positions are prescribed.
enum class ParticleKind : std::uint8_t { Fluid = 0, Wall = 1, Ghost = 2 };

/// How the new elements that are fluid are chosen among the Delaunay triangles.
///  - Alpha: the classic alpha shape (an element is kept if R <= alpha h_e); the domain is re-detected from
///    the particles alone at every remesh, so elements along the free surface appear and disappear, and the
///    fluid's area (its mass) changes with them.
///  - Advected: an element whose centroid lies in the previous domain (PreviousDomain) is kept unless it is
///    a sliver beyond the separation test (R > separation_alpha h_e: a film tearing, a jet breaking up; water
///    against a wall, RemeshSettings::on_wall, only once it has left the wall); one
///    outside it is added only if it passes the alpha test and has at most one wall or ghost particle (two
///    free surfaces, or a surface and a wall, meeting). Where the topology does not change the domain does
///    not change.
///  - LevelSet: as Advected, but an element outside the previous domain is added when its centroid lies
///    within level_set_band h_e of the previous boundary (the signed-distance filter), whatever its shape.
enum class DomainDetection : std::uint8_t { Alpha = 0, Advected = 1, LevelSet = 2 };

struct RemeshSettings {
  double alpha = 1.2;  ///< delete an element if R > alpha * h_e
  DomainDetection detection = DomainDetection::Alpha;
  const PreviousDomain* previous = nullptr;  ///< required (non-empty) unless detection is Alpha
  double separation_alpha = 2.5;             ///< Advected / LevelSet: inside elements kept while R <= this h_e
  double level_set_band = 0.25;              ///< LevelSet: outside elements within this h_e of the boundary
  double wetting_distance = 0.5;             ///< Advected / LevelSet: a dry wall particle joins the domain
                                             ///< when a fluid particle comes within this h_e of it
  /// Advected / LevelSet: an element of fluid particles only outside the previous domain (two surfaces
  /// meeting) is added only once its smallest height 2A / l_max is at most contact_gap h_e: the gap between
  /// the surfaces has nearly closed (a surface reaching a wall or ghost particle: wetting_distance). An element that
  /// closes a gap of height d adds d times its base of fluid that no particle brought; the alpha test alone accepts
  /// gaps up to about 1.5 h_e (a falling drop joins the pool a spacing before it touches it), which in a splash adds
  /// area at every landing. 0: off (the alpha test or the level-set band alone).
  double contact_gap = 0.0;
  /// Advected / LevelSet with the previous mesh's edges (PreviousDomain::set_edges): an interior edge of the
  /// previous mesh that is no longer Delaunay is flipped back while the two angles facing it sum to at most
  /// pi + keep_edges_angle (radians). The Delaunay criterion is discontinuous: a nearly cocircular quadrilateral
  /// of particles flips its diagonal back and forth as they move, and each flip changes the discrete
  /// divergence-free space the velocity lives in; this hysteresis keeps the connectivity until the quality
  /// asks for a change. 0: only the previous boundary edges are restored.
  double keep_edges_angle = 0.0;
  /// Advected / LevelSet: per particle, 1 if it lies on a wall's line (walls as constraints); nullptr: none. An
  /// element inside the previous domain with an edge along a wall (between two such particles, its midpoint on a
  /// wall's line by along_wall) leans on the wall along that edge, which cannot tear: it separates only when one of
  /// its other two edges is longer than separation_alpha h_e.
  const std::vector<std::uint8_t>* on_wall = nullptr;
  /// With on_wall: whether a point lies on a wall's line (an edge between particles on two walls that meet at a
  /// corner crosses the water). Empty: every edge between two on_wall particles runs along a wall.
  std::function<bool(const Vec2&)> along_wall{};
};

struct RemeshResult {
  std::vector<std::array<Index, 3>> triangles;      ///< kept elements, counter-clockwise
  std::vector<std::uint8_t> free_surface;           ///< per particle: 1 if a fluid particle on an unshared edge
  std::vector<std::uint8_t> connected;              ///< per particle: 1 if used by at least one kept element
  double area = 0;                                  ///< total area of the kept elements
  int removed_alpha = 0;                            ///< elements deleted by the alpha test
  int removed_boundary_only = 0;                    ///< elements deleted because all their particles are walls/ghosts
  int added_outside = 0;                            ///< Advected / LevelSet: kept elements outside the previous domain
  int separated_inside = 0;                         ///< Advected / LevelSet: elements inside it deleted (separation)
  int restored_edges = 0;                           ///< Advected / LevelSet: previous boundary edges flipped back in
  int lost_edges = 0;                               ///< Advected / LevelSet: previous boundary edges left out (crossed
                                                    ///< by more than one Delaunay edge)
  int kept_edges = 0;                               ///< keep_edges_angle > 0: previous interior edges flipped back in
  std::vector<Index> added_elements;                ///< Advected / LevelSet: indices (in `triangles`) of the kept
                                                    ///< elements outside the previous domain
  std::vector<std::array<Index, 3>> separated;      ///< Advected / LevelSet: the elements inside it deleted
  std::vector<std::array<Index, 3>> boundary_only;  ///< the Delaunay faces (not flat) whose particles are all
                                                    ///< walls/ghosts, never kept, counter-clockwise
};

/// Triangulates `points` (Delaunay, built by range insertion with spatial sorting; each vertex keeps its
/// index), then keeps an element if (1) the domain detection of `settings` accepts it (Alpha: its
/// circumradius R <= alpha * (h_a + h_b + h_c)/3; see DomainDetection for the others) and (2) at least
/// one of its particles is Fluid. Free-surface particles: Fluid particles on an edge used by exactly one
/// kept element. Duplicate points (closer than 1e-12 of the bounding box) are an error
/// (std::invalid_argument), as are sizes that do not match or fewer than 3 points (then the result is empty
/// rather than an error if all are valid: fewer than 3 points give no triangles).
/// Degenerate (zero-area) Delaunay triangles of collinear points are never kept.
RemeshResult remesh(const std::vector<Vec2>& points, const std::vector<ParticleKind>& kind,
                    const std::vector<double>& h, const RemeshSettings& settings);

class SpacePartition;

/// One part's share of remesh() over a SpacePartition of `points` (partition.hpp), for a run divided among
/// processes: the part triangulates its own particles and those within `halo` of its box (its ghosts), classifies
/// every face as remesh() does, and reports the kept faces whose centroid (computed from the vertices in increasing
/// index order, the same bits in every part) lies in its box, with their counts and lists (added_elements indexes
/// the share's triangles), the free-surface and connected flags their edges and particles give, their area, and the
/// restored, lost and kept edges whose lower particle is the part's. Over the parts the shares together are remesh()'s
/// result (each kept element once; the flags or-ed, the counts summed) when every kept face's circumdisc lies within
/// the halo of its centroid's box: with the alpha test or the advected detection every kept face has a circumradius
/// R <= max(alpha, separation_alpha) h_e and its centroid is within R of its circumcentre, so a halo of
/// 2 max(alpha, separation_alpha) max h_i suffices for the Delaunay faces (a face whose circumdisc lies where the part
/// holds every particle of the cloud is Delaunay in both or in neither); a flat element kept against a wall (on_wall)
/// may have a larger circumdisc, whose part beyond the halo lies behind the wall, where a cloud bounded by that wall
/// has no particle; the previous edges flipped back in are local
/// to their quadrilaterals, for which the caller adds a margin. The level-set detection keeps faces of any size
/// outside the previous domain and is refused (std::invalid_argument), as are a partition of other points, a part
/// out of range and a halo that is not positive. `ghost_count` (optional) receives the number of ghosts it used.
RemeshResult remesh_part(const std::vector<Vec2>& points, const std::vector<ParticleKind>& kind,
                         const std::vector<double>& h, const RemeshSettings& settings, const SpacePartition& partition,
                         int part, double halo, Index* ghost_count = nullptr);

/// The plain Delaunay triangulation of `points` (no alpha test, no removal), counter-clockwise, with the
/// same construction, validation and duplicate check as remesh(); dimension < 2 (all points collinear)
/// gives no triangles. For diagnostics, tests and timing the triangulation alone.
std::vector<std::array<Index, 3>> delaunay_triangles(const std::vector<Vec2>& points);

/// Particle-quality control, geometric part. Pairs of Fluid particles closer than `fraction * h_ij`,
/// h_ij = (h_i + h_j)/2 (fraction typically 0.3-0.5): returns the indices to remove (one per pair, never
/// a wall or ghost, each particle at most once, the one with the larger index of the pair; pairs are
/// taken closest first and a pair whose particle is already removed is skipped), found from the edges of
/// `triangles` (the nearest neighbour of a point is always a Delaunay neighbour), so this is
/// O(n + k log k) for k close pairs. Sorted ascending.
std::vector<Index> close_fluid_particles(const std::vector<Vec2>& points, const std::vector<ParticleKind>& kind,
                                         const std::vector<double>& h,
                                         const std::vector<std::array<Index, 3>>& triangles, double fraction);

/// Like close_fluid_particles, as pairs (kept, removed): the caller merges the removed particle into the
/// kept one. Same order and choice.
std::vector<std::pair<Index, Index>> close_fluid_pairs(const std::vector<Vec2>& points,
                                                       const std::vector<ParticleKind>& kind,
                                                       const std::vector<double>& h,
                                                       const std::vector<std::array<Index, 3>>& triangles,
                                                       double fraction);

/// Kept elements whose area exceeds `factor * h_e^2` (h_e as in remesh): candidates for inserting a
/// particle at their centroid (the caller interpolates the particle's state).
std::vector<Index> oversized_elements(const std::vector<Vec2>& points, const std::vector<double>& h,
                                      const std::vector<std::array<Index, 3>>& triangles, double factor);

}  // namespace lagfsi::meshing
