// The DEM force sweep and the neighbour-list maintenance (src/dem/dem_body.hpp).
//
// Race-free parallel sweep in two passes, both parallel (OpenMP), neither with a shared write:
//  A. over the pairs of the half list: kinematics, the law (templated on its class: no virtual call per
//     pair), the pair's force into pair_force[3k] (Fx, Fy on i; -ft, the torque per unit radius);
//  B. over the discs: gravity, the sum of its pairs' forces in the fixed incidence order (+F as i, -F as j;
//     torque r_p * (-ft) for both), its wall contacts, the blast force.
// Each disc's sum has a fixed order, so the result is the same for any number of threads.
//
// Lists: a Verlet half list with skin (dem_neighbour_grid.hpp), rebuilt when a disc would move more than
// skin/2 (or a disc and a moving wall come closer by more than skin) since the last build; at a rebuild the
// discs are first reordered in cell order (neighbours close in memory), and the tangential histories of the
// pairs present in both lists are carried over.
#include "dem_body.hpp"

#include <lagfsi/stopwatch.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lagfsi::dem {

namespace {

template <class Law, bool Energy>
void pair_pass(DemBody& b, const Law& law, const double* x, const double* v, double h) {
  const PairList& P = b.pairs;
  const Index np = static_cast<Index>(P.size());
  const Index* pi = P.i.data();
  const Index* pj = P.j.data();
  const double* rad = b.discs.radius.data();
  const double* mass = b.discs.mass.data();
  const std::uint8_t* mark = b.discs.mark.data();
  double* hist = b.history.data();
  double* pf = b.pair_force.data();
  std::uint8_t* rupt = b.pair_rupture.data();
  double* pe = Energy ? b.pair_elastic.data() : nullptr;
  double* pd = Energy ? b.pair_dissipated.data() : nullptr;
  const bool history = law.has_history();
  const bool rolling = law.rolling() > 0;
  const double* inertia = b.discs.inertia.data();
  double* roll = rolling ? b.pair_roll.data() : nullptr;
#pragma omp parallel for schedule(static) if (np >= 4000)
  for (Index k = 0; k < np; ++k) {
    const Index i = pi[k], j = pj[k];
    const double dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1];
    const double d2 = dx * dx + dy * dy, ri = rad[i], rj = rad[j], rs = ri + rj;
    if (d2 >= rs * rs) {
      pf[3 * k] = pf[3 * k + 1] = pf[3 * k + 2] = 0.0;
      if (history) hist[k] = 0.0;
      if (rolling) roll[k] = 0.0;
      if constexpr (Energy) pe[k] = pd[k] = 0.0;
      continue;
    }
    const double d = std::sqrt(d2), inv = 1.0 / d;
    const double nx = dx * inv, ny = dy * inv;
    const double dvx = v[3 * i] - v[3 * j], dvy = v[3 * i + 1] - v[3 * j + 1];
    const double mi = mass[i], mj = mass[j];
    ContactKinematics c;
    c.overlap = rs - d;
    c.rate = -(dvx * nx + dvy * ny);
    c.vt = -dvx * ny + dvy * nx - (ri * v[3 * i + 2] + rj * v[3 * j + 2]);
    c.m_eff = mi * mj / (mi + mj);
    c.r_eff = ri * rj / rs;
    c.r_min = std::min(ri, rj);
    c.dt = h;
    c.marked = mark[i] | mark[j];
    double tmp = 0;
    const ContactForce f = law.compute(c, history ? hist[k] : tmp);
    pf[3 * k] = f.fn * nx - f.ft * ny;
    pf[3 * k + 1] = f.fn * ny + f.ft * nx;
    pf[3 * k + 2] = -f.ft;
    if (f.rupture) rupt[k] = 1;
    if (rolling) {
      const double ii = inertia[i], ij = inertia[j];
      roll[k] = law.rolling_torque(v[3 * i + 2] - v[3 * j + 2], f.fn, c.r_eff, ii * ij / (ii + ij), h);
    }
    if constexpr (Energy) {
      pe[k] = f.elastic;
      pd[k] = f.dissipated;
    }
  }
}

template <class Law, bool Energy>
void disc_pass(DemBody& b, const Law& law, const double* x, const double* v, double t, double h, double* f) {
  const Index n = static_cast<Index>(b.size());
  const PairList& P = b.pairs;
  const Index* inc_row = P.inc_row.data();
  const Index* inc = P.inc.data();
  const double* pf = b.pair_force.data();
  const double* rad = b.discs.radius.data();
  const double* mass = b.discs.mass.data();
  const double gx = b.gravity.x(), gy = b.gravity.y();
  const bool rotation = b.rotation;
  const bool blast = !b.blast_force.empty();
  const bool walls = !b.segments.empty();
  const bool history = law.has_history();
  const bool rolling = law.rolling() > 0;
  const double* roll = rolling ? b.pair_roll.data() : nullptr;
#pragma omp parallel for schedule(static) if (n >= 2000)
  for (Index p = 0; p < n; ++p) {
    const double m = mass[p], r = rad[p];
    double fx = m * gx, fy = m * gy, tq = 0;
    for (Index e = inc_row[p]; e < inc_row[p + 1]; ++e) {
      const Index code = inc[e], k = code >> 1;
      const double s = (code & 1) ? -1.0 : 1.0;
      fx += s * pf[3 * k];
      fy += s * pf[3 * k + 1];
      tq += r * pf[3 * k + 2];
      if (rolling) tq += s * roll[k];
    }
    if (walls) {
      double el = 0, dis = 0;
      for (Index e = b.wall_row[p]; e < b.wall_row[p + 1]; ++e) {
        const auto [w, s] = b.segments[b.wall_seg[e]];
        const Wall& wall = b.walls[w];
        const Vec2 c(x[3 * p], x[3 * p + 1]);
        const Vec2 q = closest_on_segment(wall.a(s), wall.b(s), c);
        const Vec2 dv = c - q;
        const double d2 = dv.squaredNorm();
        if (d2 >= r * r || d2 == 0.0) {
          b.wall_force[2 * e] = b.wall_force[2 * e + 1] = 0.0;
          if (history) b.wall_history[e] = 0.0;
          continue;
        }
        const double d = std::sqrt(d2);
        const double nx = dv.x() / d, ny = dv.y() / d;
        const Vec2 vw = wall.velocity(t);
        const double dvx = v[3 * p] - vw.x(), dvy = v[3 * p + 1] - vw.y();
        ContactKinematics c2;
        c2.overlap = r - d;
        c2.rate = -(dvx * nx + dvy * ny);
        c2.vt = -dvx * ny + dvy * nx - r * v[3 * p + 2];
        c2.m_eff = m;
        c2.r_eff = r;
        c2.r_min = r;
        c2.dt = h;
        c2.wall = true;
        c2.marked = b.discs.mark[p];
        double tmp = 0;
        const ContactForce cf = law.compute(c2, history ? b.wall_history[e] : tmp);
        const double wx = cf.fn * nx - cf.ft * ny, wy = cf.fn * ny + cf.ft * nx;
        b.wall_force[2 * e] = wx;
        b.wall_force[2 * e + 1] = wy;
        fx += wx;
        fy += wy;
        tq -= r * cf.ft;
        if (rolling) tq += law.rolling_torque(v[3 * p + 2], cf.fn, r, b.discs.inertia[p], h);
        if (cf.rupture) b.discs.mark[p] = 1;
        el += cf.elastic;
        dis += cf.dissipated;
      }
      if constexpr (Energy) {
        b.disc_elastic[p] = el;
        b.disc_dissipated[p] = dis;
      }
    }
    if (blast) {
      fx += b.blast_force[2 * p];
      fy += b.blast_force[2 * p + 1];
    }
    f[3 * p] = fx;
    f[3 * p + 1] = fy;
    f[3 * p + 2] = rotation ? tq : 0.0;
  }
}

template <class Law>
void sweep(DemBody& b, const Law& law, const double* x, const double* v, double t, double h, double* f) {
  if (b.track_energy) {
    pair_pass<Law, true>(b, law, x, v, h);
    disc_pass<Law, true>(b, law, x, v, t, h, f);
  } else {
    pair_pass<Law, false>(b, law, x, v, h);
    disc_pass<Law, false>(b, law, x, v, t, h, f);
  }
}

}  // namespace

void DemBody::compute_forces(const Vec& x, const Vec& v, double tt, double h, Vec& f) {
  const auto t0 = SteadyClock::now();
  const Index n = static_cast<Index>(size());
  if (f.size() != 3 * n) f.resize(3 * n);
  if (blast && tt >= 0 && blast->active(tt)) {
    const auto tb = SteadyClock::now();
    blast_force.assign(2 * n, 0.0);
    blast->apply(x.data(), 3, discs.radius.data(), n, tt, blast_force);
    for (Index p = 0; p < n; ++p)
      blast_work += h * (blast_force[2 * p] * v[3 * p] + blast_force[2 * p + 1] * v[3 * p + 1]);
    t_blast += seconds_since(tb);
  } else if (!blast_force.empty()) {
    blast_force.clear();
  }
  if (track_energy) {
    pair_elastic.resize(pairs.size());
    pair_dissipated.resize(pairs.size());
    disc_elastic.assign(n, 0.0);
    disc_dissipated.assign(n, 0.0);
  }
  const ContactLaw* l = law.get();
  if (auto* a = dynamic_cast<const LinearSpringDashpot*>(l))
    sweep(*this, *a, x.data(), v.data(), tt, h, f.data());
  else if (auto* c = dynamic_cast<const HertzMindlin*>(l))
    sweep(*this, *c, x.data(), v.data(), tt, h, f.data());
  else if (auto* s = dynamic_cast<const Sabatucci*>(l))
    sweep(*this, *s, x.data(), v.data(), tt, h, f.data());
  else
    throw std::logic_error("unknown contact law " + l->type());
  if (track_energy) {
    double el = 0, dis = 0;
    for (size_t k = 0; k < pairs.size(); ++k) {
      el += pair_elastic[k];
      dis += pair_dissipated[k];
    }
    for (Index p = 0; p < n; ++p) {
      el += disc_elastic[p];
      dis += disc_dissipated[p];
    }
    elastic = el;
    dissipated += dis;
  }
  t_force += seconds_since(t0);
}

void DemBody::apply_marks() {
  for (size_t k = 0; k < pairs.size(); ++k)
    if (pair_rupture[k]) {
      discs.mark[pairs.i[k]] = 1;
      discs.mark[pairs.j[k]] = 1;
      pair_rupture[k] = 0;
    }
}

void DemBody::place_walls(double tt) {
  for (auto& w : walls) w.offset = w.displacement(tt);
}

bool DemBody::needs_rebuild(double h) const {
  const Index n = static_cast<Index>(size());
  const double* x = state.x.data();
  const double* v = state.v.data();
  const double* a = state.a.data();
  const double h2 = 0.5 * h * h;
  double m2 = 0;
#pragma omp parallel for schedule(static) reduction(max : m2) if (n >= 20000)
  for (Index p = 0; p < n; ++p) {
    const double dx = x[3 * p] + h * v[3 * p] + h2 * a[3 * p] - x_build[2 * p];
    const double dy = x[3 * p + 1] + h * v[3 * p + 1] + h2 * a[3 * p + 1] - x_build[2 * p + 1];
    m2 = std::max(m2, dx * dx + dy * dy);
  }
  const double md = std::sqrt(m2);
  if (2 * md > skin) return true;
  for (size_t w = 0; w < walls.size(); ++w) {
    if (!walls[w].moving()) continue;
    const double wd = (walls[w].displacement(state.t + h) - wall_offset_build[w]).norm();
    if (md + wd > skin) return true;
  }
  return false;
}

void DemBody::rebuild() {
  const auto t0 = SteadyClock::now();
  const Index n = static_cast<Index>(size());
  const double cell = 2 * r_max + skin;
  grid.bin(state.x.data(), 3, n, cell);
  std::vector<Index> perm;  // new -> old
  if (reorder) {
    perm = grid.order();
    auto permute_vec = [&](Vec& a) {
      Vec o(a.size());
      for (Index s = 0; s < n; ++s)
        for (int c = 0; c < 3; ++c) o[3 * s + c] = a[3 * perm[s] + c];
      a.swap(o);
    };
    permute_vec(state.x);
    permute_vec(state.v);
    permute_vec(state.a);
    permute_vec(inv_mass);
    auto permute = [&](auto& a) {
      auto o = a;
      for (Index s = 0; s < n; ++s) o[s] = a[perm[s]];
      a.swap(o);
    };
    permute(discs.radius);
    permute(discs.mass);
    permute(discs.inertia);
    permute(discs.id);
    permute(discs.mark);
    permute(discs.group);
    grid.bin(state.x.data(), 3, n, cell);
    if (blast) blast->invalidate();
  }
  for (Index p = 0; p < n; ++p) where[discs.id[p]] = p;
  // pair list, with the histories carried over
  PairList fresh;
  grid.build(state.x.data(), 3, discs.radius.data(), n, skin, fresh);
  std::vector<double> hist(fresh.size(), 0.0);
  if (law->has_history() && !pairs.i.empty()) {
    const Index m = static_cast<Index>(fresh.size());
#pragma omp parallel for schedule(static) if (m >= 20000)
    for (Index k = 0; k < m; ++k) {
      const Index a = reorder ? perm[fresh.i[k]] : fresh.i[k], c = reorder ? perm[fresh.j[k]] : fresh.j[k];
      const Index old = pairs.find(a, c);
      if (old >= 0) hist[k] = history[old];
    }
  }
  // wall list (CSR by disc), with the histories carried over
  std::vector<Index> wrow(n + 1, 0), wseg;
  std::vector<double> whist;
  for (Index p = 0; p < n; ++p) {
    const Vec2 c(state.x[3 * p], state.x[3 * p + 1]);
    const double reach = discs.radius[p] + skin;
    for (size_t s = 0; s < segments.size(); ++s) {
      const Wall& w = walls[segments[s].first];
      const Vec2 q = closest_on_segment(w.a(segments[s].second), w.b(segments[s].second), c);
      if ((q - c).squaredNorm() >= reach * reach) continue;
      wseg.push_back(static_cast<Index>(s));
      double hh = 0;
      if (law->has_history() && !wall_row.empty()) {
        const Index old = reorder ? perm[p] : p;
        for (Index e = wall_row[old]; e < wall_row[old + 1]; ++e)
          if (wall_seg[e] == static_cast<Index>(s)) hh = wall_history[e];
      }
      whist.push_back(hh);
    }
    wrow[p + 1] = static_cast<Index>(wseg.size());
  }
  pairs = std::move(fresh);
  history = std::move(hist);
  pair_force.assign(3 * pairs.size(), 0.0);
  pair_rupture.assign(pairs.size(), 0);
  if (law->rolling() > 0) pair_roll.assign(pairs.size(), 0.0);
  wall_row = std::move(wrow);
  wall_seg = std::move(wseg);
  wall_history = std::move(whist);
  wall_force.assign(2 * wall_seg.size(), 0.0);
  x_build.resize(2 * n);
  for (Index p = 0; p < n; ++p) {
    x_build[2 * p] = state.x[3 * p];
    x_build[2 * p + 1] = state.x[3 * p + 1];
  }
  wall_offset_build.resize(walls.size());
  for (size_t w = 0; w < walls.size(); ++w) wall_offset_build[w] = walls[w].offset;
  ++rebuilds;
  t_rebuild += seconds_since(t0);
}

double DemBody::kinetic_energy() const {
  double e = 0;
  for (size_t p = 0; p < size(); ++p)
    e += 0.5 * discs.mass[p] * (state.v[3 * p] * state.v[3 * p] + state.v[3 * p + 1] * state.v[3 * p + 1]);
  return e + rotational_energy();
}

double DemBody::rotational_energy() const {
  if (!rotation) return 0.0;
  double e = 0;
  for (size_t p = 0; p < size(); ++p) e += 0.5 * discs.inertia[p] * state.v[3 * p + 2] * state.v[3 * p + 2];
  return e;
}

double DemBody::gravity_potential() const {
  double e = 0;
  for (size_t p = 0; p < size(); ++p)
    e -= discs.mass[p] * (gravity.x() * state.x[3 * p] + gravity.y() * state.x[3 * p + 1]);
  return e;
}

int DemBody::contact_count() const {
  int c = 0;
  for (size_t k = 0; k < pairs.size(); ++k)
    if (pair_force[3 * k] != 0.0 || pair_force[3 * k + 1] != 0.0) ++c;
  for (size_t e = 0; e < wall_seg.size(); ++e)
    if (wall_force[2 * e] != 0.0 || wall_force[2 * e + 1] != 0.0) ++c;
  return c;
}

double DemBody::max_contact_force() const {
  double m = 0;
  for (size_t k = 0; k < pairs.size(); ++k) m = std::max(m, std::hypot(pair_force[3 * k], pair_force[3 * k + 1]));
  for (size_t e = 0; e < wall_seg.size(); ++e) m = std::max(m, std::hypot(wall_force[2 * e], wall_force[2 * e + 1]));
  return m;
}

}  // namespace lagfsi::dem
