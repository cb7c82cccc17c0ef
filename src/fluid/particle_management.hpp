#pragma once
/// @file particle_management.hpp (private to src/fluid)
/// What the stages of RemeshPipeline::manage_particles share (particle_management.cpp), and in an MPI run the
/// particles divided among the processes by space for its searches (divided_management.cpp).
#include "point_grid.hpp"
#include "remesh_pipeline.hpp"

#include <lagfsi/meshing/partition.hpp>
#include <lagfsi/mpi_run.hpp>

#include <initializer_list>
#include <memory>
#include <vector>

namespace lagfsi::fluid {

/// What the stages of manage_particles share: the cloud at the start (positions and lumped masses; a merge
/// moves its survivor in the cloud, not in `pts`), what becomes of each particle, the particles to insert and
/// the previous mesh's edges through these changes.
struct RemeshPipeline::Management {
  using NewParticle = RemeshPipeline::NewParticle;

  Management(const BoundaryChains& chain, const std::vector<char>& on_wall) : chain(chain), on_wall(on_wall) {}

  const BoundaryChains& chain;
  const std::vector<char>& on_wall;
  Index np = 0;                                   // particles at the start
  std::vector<Vec2> pts;                          // their positions at the start
  std::vector<double> lumped;                     // their masses: the lumped areas sum_e A_e / 3
  std::vector<char> drop, touched;                // removed; merged or removed (its elements are gone)
  std::vector<Index> alias;                       // a merged particle's survivor (itself otherwise)
  std::vector<Index> heir;                        // a particle removed at a wall: the wall particle that stands for it
  std::vector<NewParticle> fresh;                 // the particles to insert, numbered np, np + 1, ...
  std::vector<Index> split_at;                    // boundary edge from a (to chain.next[a]) split by new particle k
  std::unique_ptr<PointGrid> taken;               // the occupied spots (walls as constraints: occupy_spots)
  std::vector<Vec2> taken_pts;                    // their positions
  double r_taken = 0;                             // no new particle closer than this times its size to an occupied spot
  std::vector<std::uint8_t> used;                 // the particles the previous mesh used (new ones: 0)
  std::vector<std::pair<Index, Index>> edges;     // its boundary edges through merges and splits
  std::vector<std::pair<Index, Index>> interior;  // its other edges through merges (when all_edges is asked)

  /// An MPI run (mpi_run.hpp): the particles at the start divided among the processes by space (a recursive
  /// coordinate bisection), each process searching for its own; none with one process.
  std::unique_ptr<meshing::SpacePartition> part;

  /// True when this process searches for particle i (every particle with one process).
  bool mine(Index i) const { return !part || part->owner()[static_cast<size_t>(i)] == mpi_run::rank(); }
  /// The number of a particle's components constrained by a wall (0 without walls as constraints).
  int walled(Index i) const { return on_wall.empty() ? 0 : int(on_wall[static_cast<size_t>(i)]); }
  bool on_boundary(Index i) const { return chain.next[i] >= 0 || chain.prev[i] >= 0; }

  /// The weighted mean sum_k w_k (state of ids[k]) of the particles' states, at their starting positions.
  NewParticle between(const ParticleCloud& cloud, const std::vector<Index>& ids, const std::vector<double>& w) const {
    NewParticle q{Vec2::Zero(), Vec2::Zero(), Vec2::Zero(), 0.0, 0.0};
    for (size_t k = 0; k < ids.size(); ++k) {
      q.x += w[k] * pts[ids[k]];
      q.v += w[k] * cloud.v().segment<2>(2 * ids[k]);
      q.a += w[k] * cloud.a().segment<2>(2 * ids[k]);
      q.p += w[k] * cloud.p()[ids[k]];
      q.h += w[k] * cloud.h(ids[k]);
    }
    return q;
  }

  /// Walls as constraints: many particles lie on one line (a floor), and one outside the mesh (just let go,
  /// or landed) may sit on a boundary edge between two others: no new particle within r (max(close_fraction, 0.05) h)
  /// of an existing one. The particles that stay occupy their spots; only those within r h_max of a spot the stages
  /// will ask for (`asked`: the new particles' positions) can make one taken, so only they are put in the grid (an
  /// MPI run: each process finds its own, and every process gets them all).
  void occupy_spots(double r, double h_max, std::initializer_list<const std::vector<NewParticle>*> asked) {
    r_taken = r;
    const double reach = std::max(r_taken * h_max, 1e-300);
    std::vector<Vec2> spots;
    for (const auto* list : asked)
      for (const NewParticle& q : *list) spots.push_back(q.x);
    taken = std::make_unique<PointGrid>(reach, spots.size());
    taken_pts.clear();
    if (spots.empty()) return;
    PointGrid grid(reach, spots.size());
    for (size_t k = 0; k < spots.size(); ++k) grid.add(spots[k], static_cast<Index>(k));
    std::vector<Index> near;
    for (Index i = 0; i < np; ++i)  // a hair wider: a new particle's h is a mean of the particles' sizes
      if (!drop[i] && mine(i) && grid.find(pts[i], reach * (1 + 1e-12), spots) >= 0) near.push_back(i);
    if (part) near = mpi_run::gather_all(near);
    for (Index i : near) {
      taken->add(pts[i], static_cast<Index>(taken_pts.size()));
      taken_pts.push_back(pts[i]);
    }
  }
  /// True when x is free for a particle of size h (always without occupy_spots); a free spot is then occupied.
  bool free_spot(const Vec2& x, double h) {
    if (!taken) return true;
    if (taken->find(x, r_taken * h, taken_pts) >= 0) return false;
    taken->add(x, static_cast<Index>(taken_pts.size()));
    taken_pts.push_back(x);
    return true;
  }
};

}  // namespace lagfsi::fluid
