// Volume corrections of the PFEM fluid (volume_correction.hpp): "surface" (restore_area), "source" (c_vol)
// and "particle" (owe_remesh_change, set_end, owed_rate).
#include "volume_correction.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace lagfsi::fluid {

void VolumeCorrection::restore_area(const std::vector<char>& still) {
  // Remeshing changes the fluid's area: the alpha shape closes or opens elements along the free surface
  // (a splash joining the pool, a film tearing), and inserted or removed particles shift it. The error is
  // geometric and sits on the free surface, so it is removed there, before the step is solved: the
  // free-surface particles move along the gradient of the mesh area, g_i = dA/dx_i = sum_e (A_e grad N_i)
  // (zero at interior particles, (1/2) J (x_next - x_prev) on the boundary), by the smallest such motion
  // that restores the reference area to first order, dx_i = lambda g_i, lambda = (A_ref - A) / sum |g_i|^2
  // (two passes close the second-order remainder). No velocity changes and no pressure is needed (the
  // "source" correction needs a pressure of order rho L^2 (error) / T^2 to contract the whole fluid). Each
  // pass moves a particle by at most 0.05 h; a larger error is closed over several steps.
  if (!(area_ref_ > 0)) return;
  const Index np = cloud_.n();
  const std::vector<ParticleKind>& kind = cloud_.kind();
  const std::vector<std::array<Index, 3>>& tri = mesh_.tri;
  Vec& x = cloud_.x();
  // Only the surface of the bulk moves: a free-surface particle of an element with an interior fluid
  // particle. Films, jets and drops (elements of free-surface particles only) keep their positions: their
  // continuity rows are not solved (p = 0 on the free surface), and a push along their thin outline would
  // accumulate at their tips (the front of a dam break runs ahead by a film).
  std::vector<char> movable = mesh_.beside_interior_fluid(kind);
  const std::vector<char> at_wall = mesh_.in_element_with(np, [&](Index i) { return kind[i] != ParticleKind::Fluid; });
  for (Index i = 0; i < np; ++i)
    movable[i] = movable[i] && kind[i] == ParticleKind::Fluid && mesh_.free[i] && !at_wall[i] &&
                 !(static_cast<size_t>(i) < still.size() && still[static_cast<size_t>(i)]);
  const auto area2 = [](const Vec2& a, const Vec2& b, const Vec2& c) {  // twice the signed area
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  Vec g(2 * np);
  std::vector<double> lumped(np);  // lumped areas (the particles' masses / rho): the potential energy
                                   // the correction moves is counted (probe volume_correction_energy)
  for (int pass = 0; pass < 2; ++pass) {
    double area = 0;
    g.setZero();
    std::fill(lumped.begin(), lumped.end(), 0.0);
    for (Index e = 0; e < static_cast<Index>(tri.size()); ++e) {
      const auto& t = tri[e];
      const Vec2 xa = x.segment<2>(2 * t[0]), xb = x.segment<2>(2 * t[1]), xc = x.segment<2>(2 * t[2]);
      const double Ae = 0.5 * area2(xa, xb, xc);
      area += Ae;
      for (Index i : t) lumped[i] += Ae / 3.0;
      const Vec2 xs[3] = {xa, xb, xc};
      for (int k = 0; k < 3; ++k) {
        const Vec2& q = xs[(k + 1) % 3];
        const Vec2& r = xs[(k + 2) % 3];
        g.segment<2>(2 * t[k]) += 0.5 * Vec2(q.y() - r.y(), r.x() - q.x());
      }
    }
    const double error = area_ref_ - area;
    if (std::abs(error) <= 1e-12 * area_ref_) return;
    // A particle whose move would shrink one of its elements below half its area (a sliver at a splash)
    // stays where it is; lambda is then recomputed over the others.
    double lambda = 0;
    for (int guard = 0; guard < 4; ++guard) {
      double gg = 0, gmax = 0;
      for (Index i = 0; i < np; ++i) {
        if (!movable[i]) continue;
        gg += g.segment<2>(2 * i).squaredNorm();
        gmax = std::max(gmax, g.segment<2>(2 * i).norm() / cloud_.h(i));
      }
      if (!(gg > 0)) return;
      lambda = error / gg;
      if (std::abs(lambda) * gmax > 0.05) lambda = std::copysign(0.05 / gmax, lambda);
      bool frozen = false;
      for (const auto& t : tri) {
        if (!(movable[t[0]] || movable[t[1]] || movable[t[2]])) continue;
        Vec2 y[3];
        for (int k = 0; k < 3; ++k)
          y[k] = x.segment<2>(2 * t[k]) + (movable[t[k]] ? lambda : 0.0) * g.segment<2>(2 * t[k]);
        const Vec2 xa = x.segment<2>(2 * t[0]), xb = x.segment<2>(2 * t[1]), xc = x.segment<2>(2 * t[2]);
        if (area2(y[0], y[1], y[2]) < 0.5 * area2(xa, xb, xc)) {
          for (Index i : t) movable[i] = 0;
          frozen = true;
        }
      }
      if (!frozen) break;
      if (guard == 3) return;
    }
    for (Index i = 0; i < np; ++i) {
      if (!movable[i]) continue;
      x.segment<2>(2 * i) += lambda * g.segment<2>(2 * i);
      correction_energy_ -= c_.rho * lumped[i] * c_.gravity.dot(lambda * g.segment<2>(2 * i));
    }
  }
}

void VolumeCorrection::set_remeshed(double area, double dt) {
  area_remesh_ = area;
  // Volume correction "source": a uniform source in the continuity equation, div v = -e_f/(A_ref T), that
  // closes the area error of remeshing e = A - A_ref (alpha shape, inserted/removed particles) over the
  // relaxation time T. The pressure it needs scales like rho L^2 (error)/T^2, so T must stay long compared with
  // dt; then it cannot keep up with a splash (and contracting thin regions lets the alpha shape close more
  // elements): the alpha shape's default is the "surface" correction (restore_area) instead.
  // e jumps from step to step by a fraction of an element wherever particles enter, leave or are merged (an
  // outlet's ragged end), and in a confined flow every change of the source from one step to the next moves the
  // whole column of water within the step: a pressure of order rho L (dc A / H) / dt. The source therefore acts on
  // e low-pass filtered, de_f/dt = (e - e_f)/tau with tau = T/2: the drift is still returned in full (a constant
  // e_f = e in the steady state), the loop de/dt = -e_f/T, de_f/dt = (e - e_f)/tau has the damping ratio
  // sqrt(T/tau)/2 = 0.71, and a change of e reaches the source over tau, not within one step.
  const double e = area_remesh_ - area_ref_;
  const double tau = 0.5 * relax_time_;
  error_filtered_step_ = error_filtered_ + std::min(1.0, dt / tau) * (e - error_filtered_);
  c_vol_ = type_ == Type::source && area_ref_ > 0 ? error_filtered_step_ / (area_ref_ * relax_time_) : 0.0;
  if (type_ == Type::particle) nodal_start_ = mesh_.nodal_areas(cloud_.x(), cloud_.n());
}

void VolumeCorrection::set_end(double area) {
  error_filtered_ = error_filtered_step_;
  change_in_steps_ += area - area_remesh_;
  area_end_ = area;
  if (type_ != Type::particle || nodal_start_.size() != static_cast<size_t>(cloud_.n())) return;
  // Volume correction "particle": the particles carry the fluid's mass (rho times their share of the
  // area at the start), as in SPH and MPS, where an incompressible step keeps each particle's density (the
  // density-invariance source of Asai, Aly, Sonoda & Sakai 2012, J. Appl. Math. 139583, relaxed over T).
  // The step changed each particle's share on the same mesh, without re-triangulation: the change is
  // owed back to it, and its continuity row asks for it, sum_e (A_e / 3) div v = owed_i / T.
  const std::vector<double> end = mesh_.nodal_areas(cloud_.x(), cloud_.n());
  Vec& owed = cloud_.owed();
  for (size_t i = 0; i < end.size(); ++i) owed[static_cast<Index>(i)] -= end[i] - nodal_start_[i];
  in_flight_ = 0;
  for (Index i = 0; i < cloud_.n(); ++i)
    if (i >= static_cast<Index>(mesh_.connected.size()) || !mesh_.connected[i]) in_flight_ += owed[i];
  if (area_initial_ > 0)
    water_drift_max_ =
        std::max(water_drift_max_, std::abs((water_area() + area_left_ - area_entered_) / area_initial_ - 1.0));
}

void VolumeCorrection::owe_remesh_change(const std::vector<double>& before, const std::vector<Index>& present) {
  if (type_ != Type::particle) return;
  const Index np = cloud_.n();
  // Each present particle's share on the new mesh against the shares it had (a merged particle: both).
  std::vector<double> change = mesh_.nodal_areas(cloud_.x(), np);
  for (size_t i = 0; i < before.size() && i < present.size(); ++i)
    if (present[i] >= 0) change[static_cast<size_t>(present[i])] -= before[i];
  // Groups of changed particles connected by the new mesh (union-find with path halving).
  std::vector<Index> root(static_cast<size_t>(np));
  std::iota(root.begin(), root.end(), Index{0});
  const auto find = [&](Index i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  const double h = c_.h;
  std::vector<char> changed(static_cast<size_t>(np), 0);
  for (Index i = 0; i < np; ++i) changed[i] = std::abs(change[i]) > 1e-12 * h * h;
  for (const auto& t : mesh_.tri)
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k], b = t[(k + 1) % 3];
      if (changed[a] && changed[b]) root[find(a)] = find(b);
    }
  // A particle in no element of the new mesh (a drop that left the mesh) forms its own group. A group of wall
  // or ghost particles only (their elements with the fluid changed, its particles did not) owes to them: they
  // hand it to the fluid at the step's start (hand_owed_inward). Every changed particle has |change| > 0, so
  // every group has someone to owe its net change.
  std::vector<double> net(static_cast<size_t>(np), 0.0), fluid(static_cast<size_t>(np), 0.0),
      all(static_cast<size_t>(np), 0.0);
  const std::vector<ParticleKind>& kind = cloud_.kind();
  for (Index i = 0; i < np; ++i) {
    if (!changed[i]) continue;
    const Index r = find(i);
    net[r] += change[i];
    all[r] += std::abs(change[i]);
    if (kind[i] == ParticleKind::Fluid) fluid[r] += std::abs(change[i]);
  }
  Vec& owed = cloud_.owed();
  for (Index i = 0; i < np; ++i) {
    if (!changed[i]) continue;
    const Index r = find(i);
    const bool to_fluid = fluid[r] > 0;
    if (to_fluid && kind[i] != ParticleKind::Fluid) continue;
    owed[i] -= net[r] * std::abs(change[i]) / (to_fluid ? fluid[r] : all[r]);
  }
}

void VolumeCorrection::hand_owed_inward(const std::vector<char>& fixed) {
  if (type_ != Type::particle) return;
  const Index np = cloud_.n();
  const auto row = [&](Index i) { return has_row(i, fixed); };
  std::vector<int> takers(static_cast<size_t>(np), 0);  // per prescribed particle: (element, particle) pairs
  for (const auto& t : mesh_.tri)
    for (Index i : t)
      if (!row(i))
        for (Index j : t) takers[i] += row(j) ? 1 : 0;
  Vec& owed = cloud_.owed();
  const Vec given = owed;
  for (const auto& t : mesh_.tri)
    for (Index i : t)
      if (!row(i) && takers[i] > 0 && given[i] != 0.0)
        for (Index j : t)
          if (row(j)) owed[j] += given[i] / takers[i];
  for (Index i = 0; i < np; ++i)
    if (!row(i) && takers[i] > 0) owed[i] = 0.0;
}

void VolumeCorrection::return_owed_by_moves(const std::vector<char>& fixed, const std::vector<char>& held) {
  if (type_ != Type::particle) return;
  const Index np = cloud_.n();
  const std::vector<std::array<Index, 3>>& tri = mesh_.tri;
  Vec& x = cloud_.x();
  Vec& owed = cloud_.owed();
  const std::vector<double> before = mesh_.nodal_areas(x, np);
  Vec g = Vec::Zero(2 * np);
  for (const auto& t : tri)
    for (int k = 0; k < 3; ++k) {
      const Vec2 q = x.segment<2>(2 * t[(k + 1) % 3]), r = x.segment<2>(2 * t[(k + 2) % 3]);
      g.segment<2>(2 * t[k]) += 0.5 * Vec2(q.y() - r.y(), r.x() - q.x());
    }
  Vec dx = Vec::Zero(2 * np);
  for (Index i = 0; i < np; ++i) {
    if (has_row(i, fixed) || cloud_.kind(i) != ParticleKind::Fluid || !(before[i] > 0) || owed[i] == 0.0) continue;
    for (int c = 0; c < 2; ++c)
      if (static_cast<size_t>(2 * i + c) < held.size() && held[2 * i + c]) g[2 * i + c] = 0.0;
    const double gg = g.segment<2>(2 * i).squaredNorm();
    if (!(gg > 0)) continue;
    Vec2 d = owed[i] / gg * g.segment<2>(2 * i);

    const double cap = 0.1 * cloud_.h(i);
    if (d.norm() > cap) d *= cap / d.norm();
    dx.segment<2>(2 * i) = d;
  }
  // A move that would shrink an element below half its area (a sliver) is not made.
  const auto area2 = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  for (int pass = 0; pass < 3; ++pass) {
    bool frozen = false;
    for (const auto& t : tri) {
      if (dx.segment<2>(2 * t[0]).isZero() && dx.segment<2>(2 * t[1]).isZero() && dx.segment<2>(2 * t[2]).isZero())
        continue;
      Vec2 y[3], z[3];
      for (int k = 0; k < 3; ++k) {
        z[k] = x.segment<2>(2 * t[k]);
        y[k] = z[k] + dx.segment<2>(2 * t[k]);
      }
      if (area2(y[0], y[1], y[2]) < 0.5 * area2(z[0], z[1], z[2])) {
        for (Index i : t) dx.segment<2>(2 * i).setZero();
        frozen = true;
      }
    }
    if (!frozen) break;
  }
  // The area a move adds is taken from the mover's debt (not from the neighbours whose shares it also changes):
  // first order g_i . dx_i each, the second-order rest in proportion.
  const double area_before = std::accumulate(before.begin(), before.end(), 0.0);
  x += dx;
  const std::vector<double> after = mesh_.nodal_areas(x, np);
  const double added = std::accumulate(after.begin(), after.end(), 0.0) - area_before;
  double first = 0;
  for (Index i = 0; i < np; ++i) first += g.segment<2>(2 * i).dot(dx.segment<2>(2 * i));
  if (first == 0.0) return;
  for (Index i = 0; i < np; ++i) {
    if (dx.segment<2>(2 * i).isZero()) continue;
    owed[i] -= g.segment<2>(2 * i).dot(dx.segment<2>(2 * i)) * added / first;
    correction_energy_ -= c_.rho * before[i] * c_.gravity.dot(dx.segment<2>(2 * i));
  }
}

void VolumeCorrection::return_unpayable_through_bulk(const std::vector<char>& fixed) {
  if (type_ != Type::particle) return;
  // A particle owed less than minus its share is asked to give more area than its elements have: its source
  // -owed/T pulls them inside out at any time step. It happens at a film's or a jet's tip, where remesh after
  // remesh takes area around the same few particles (dam_break_obstacle: a jet's tip owed -3.6 h^2 held at
  // -97 kPa, an element turned over at every step down to dt/16). What it cannot give beyond its share goes to
  // the particles inside the water (a continuity row, not on the free surface), in proportion to their
  // shares: still returned, by the bulk rather than where it was taken.
  const Index np = cloud_.n();
  if (nodal_start_.size() != static_cast<size_t>(np)) return;
  const std::vector<double>& share = nodal_start_;  // the step's starting shares (set_remeshed)
  const auto row = [&](Index i) { return has_row(i, fixed); };
  const auto bulk = [&](Index i) {
    return row(i) && share[i] > 0 && static_cast<size_t>(i) < mesh_.free.size() && !mesh_.free[i];
  };
  double bulk_area = 0;
  for (Index i = 0; i < np; ++i)
    if (bulk(i)) bulk_area += share[i];
  if (!(bulk_area > 0)) return;
  Vec& owed = cloud_.owed();
  double excess = 0;
  for (Index i = 0; i < np; ++i)
    if (row(i) && share[i] > 0 && owed[i] < -share[i]) {
      excess += owed[i] + share[i];
      owed[i] = -share[i];
    }
  if (excess == 0) return;
  for (Index i = 0; i < np; ++i)
    if (bulk(i)) owed[i] += excess * share[i] / bulk_area;
  returned_through_bulk_ -= excess;
}

Json VolumeCorrection::summary() const {
  Json s = {
      {"initial", area_initial_},
      {"final", area_end_},
      {"left_domain", area_left_},
      {"drift_without_left", area_initial_ > 0 ? (area_end_ + area_left_ - area_entered_) / area_initial_ - 1.0 : 0.0},
      {"change_by_remeshing", area_end_ - area_initial_ - change_in_steps_ - area_entered_},
      {"change_in_steps", change_in_steps_}};
  if (area_entered_ > 0) s["entered_domain"] = area_entered_;
  if (type_ == Type::particle) {
    s["owed_by_particles"] = cloud_.owed().sum();  // not yet returned (initial = final + owed + left)
    s["in_flight"] = in_flight_;
    s["water_drift_max"] = water_drift_max_;
    s["returned_through_bulk"] = returned_through_bulk_;
  }
  return s;
}

}  // namespace lagfsi::fluid
