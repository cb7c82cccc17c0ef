#pragma once
/// @file particle_management.hpp (private to src/fluid)
/// What the stages of RemeshPipeline::manage_particles share (particle_management.cpp), and in an MPI run the
/// particles divided among the processes by space for its searches (divided_management.cpp).
#include "point_grid.hpp"
#include "remesh_pipeline.hpp"

#include <lagfsi/meshing/partition.hpp>
#include <lagfsi/mpi_run.hpp>

#include <memory>
#include <vector>

namespace lagfsi::fluid {

/// What the stages of manage_particles share: the cloud at the start (positions and lumped masses; a merge
/// moves its survivor in the cloud, not in `pts`), what becomes of each particle, the particles to insert and
/// the previous mesh's edges through these changes.
struct RemeshPipeline::Management {
  /// A particle to insert: its state interpolated on the advected mesh.
  struct NewParticle {
    Vec2 x, v, a;
    double p, h;
  };

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
  /// of an existing one. The particles that stay occupy their spots.
  void occupy_spots(double r, double h_max) {
    r_taken = r;
    taken = std::make_unique<PointGrid>(std::max(r_taken * h_max, 1e-300), static_cast<std::size_t>(np));
    for (Index i = 0; i < np; ++i)
      if (!drop[i]) taken->add(pts[i], i);
    taken_pts = pts;
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
