// Ghost particles of a coupled structure's wet boundary (ghosts.hpp): adding them to the cloud, their
// prescribed motion, and the mesh queries that involve them.
#include "ghosts.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace lagfsi::fluid {

int Ghosts::add(const std::vector<Vec2>& points, const std::vector<std::pair<Index, Index>>& adjacent,
                ParticleCloud& cloud, double h, const std::string& body) {
  if (ghost_particles_ > 0 || !ghost_index_.empty())
    throw std::invalid_argument("body '" + body + "': only one coupled structure per fluid in this version");
  const Vec& xs = cloud.x();
  Index n_wall = 0;
  while (n_wall < cloud.n() && cloud.kind(n_wall) == ParticleKind::Wall) ++n_wall;
  ghost_begin_ = n_wall;
  // Ghosts on a wall particle are merged with it; the others become new particles after the walls.
  std::vector<Vec2> fresh;
  std::vector<Index> local(points.size(), -1);
  int merged = 0;
  for (size_t g = 0; g < points.size(); ++g) {
    Index found = -1;
    for (Index j = 0; j < n_wall && found < 0; ++j)
      if ((xs.segment<2>(2 * j) - points[g]).norm() < 0.25 * h) found = j;
    if (found >= 0) {
      ghost_index_.push_back(found);
      ghost_merged_.push_back(1);
      ++merged;
    } else {
      local[g] = static_cast<Index>(fresh.size());
      ghost_index_.push_back(n_wall + static_cast<Index>(fresh.size()));
      ghost_merged_.push_back(0);
      fresh.push_back(points[g]);
    }
  }
  ghost_particles_ = static_cast<Index>(fresh.size());
  ghost_neighbours_.assign(fresh.size(), {});
  // Neighbours along the structure, as particle indices: a ghost merged with a wall particle is that wall
  // particle (the foot of a plate clamped on the floor), so the face's first segment is kept too.
  for (const auto& [a, b] : adjacent) {
    if (local[a] >= 0) ghost_neighbours_[local[a]].push_back(ghost_index_[b]);
    if (local[b] >= 0) ghost_neighbours_[local[b]].push_back(ghost_index_[a]);
  }
  // Rebuild the cloud: walls, ghosts, then the fluid particles not within h/2 of a ghost.
  const Index np = cloud.n();
  std::vector<Index> order;
  for (Index i = 0; i < n_wall; ++i) order.push_back(i);
  std::vector<ParticleCloud::Particle> ghosts;
  for (const auto& q : fresh) {
    // The ghost starts with the initial pressure of the nearest fluid particle (the fractional step
    // corrects pressures by increments, so a ghost started at zero would keep a wrong load for many steps).
    ParticleCloud::Particle gp;
    gp.kind = ParticleKind::Ghost;
    gp.h = h;
    gp.x = q;
    gp.X0 = q;
    double best = std::numeric_limits<double>::infinity();
    for (Index i = n_wall; i < np; ++i) {
      const double d = (xs.segment<2>(2 * i) - q).squaredNorm();
      if (cloud.kind(i) == ParticleKind::Fluid && d < best) {
        best = d;
        gp.p = cloud.p()[i];
      }
    }
    order.push_back(-1 - static_cast<Index>(ghosts.size()));
    ghosts.push_back(gp);
  }
  for (Index i = n_wall; i < np; ++i) {
    bool near = false;
    for (const auto& q : fresh) near = near || (xs.segment<2>(2 * i) - q).norm() < 0.5 * h;
    if (!near) order.push_back(i);
  }
  cloud.rebuild(order, ghosts);
  ghost_force_ = Vec::Zero(2 * static_cast<Index>(points.size()));
  return merged;
}

bool Ghosts::crosses_structure(const std::array<Index, 3>& t) const {
  for (int k = 0; k < 3; ++k) {
    const Index i = t[k], j = t[(k + 1) % 3];
    if (!is_ghost(i) || !is_ghost(j)) continue;
    const auto& nb = ghost_neighbours_[i - ghost_begin_];
    if (std::find(nb.begin(), nb.end(), j) == nb.end()) return true;
  }
  return false;
}

const std::vector<Index>& Ghosts::face_neighbours(Index i) const {
  static const std::vector<Index> none;
  return is_ghost(i) ? ghost_neighbours_[static_cast<size_t>(i - ghost_begin_)] : none;
}

void Ghosts::set_motion(const Vec& x, const Vec& v, const Vec& a, const std::string& body) {
  const Index ng = static_cast<Index>(ghost_index_.size());
  if (x.size() != 2 * ng || v.size() != 2 * ng || a.size() != 2 * ng)
    throw SolverError("body '" + body + "': ghost motion of the wrong size");
  ghost_x_ = x;
  ghost_v_ = v;
  ghost_a_ = a;
}

void Ghosts::place(Vec& x) const {
  if (ghost_x_.size() == 0) return;
  for (size_t g = 0; g < ghost_index_.size(); ++g)
    if (!ghost_merged_[g]) x.segment<2>(2 * ghost_index_[g]) = ghost_x_.segment<2>(2 * g);
}

void Ghosts::set_rates(Vec& v, Vec& a) const {
  if (ghost_v_.size() == 0) return;
  for (size_t g = 0; g < ghost_index_.size(); ++g) {
    if (ghost_merged_[g]) continue;
    v.segment<2>(2 * ghost_index_[g]) = ghost_v_.segment<2>(2 * g);
    a.segment<2>(2 * ghost_index_[g]) = ghost_a_.segment<2>(2 * g);
  }
}

void Ghosts::update_contact(const FluidMesh& mesh) {
  contact_ = false;
  for (const auto& t : mesh.tri)
    for (Index i : t) contact_ = contact_ || is_ghost(i);
}

}  // namespace lagfsi::fluid
