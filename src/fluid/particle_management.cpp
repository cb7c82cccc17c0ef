// PFEM remeshing that keeps the fluid and its energy (RemeshPipeline, remesh_pipeline.hpp, with
// "domain_detection": "advected" or "level_set"; the remesh step itself is RemeshPipeline::remesh_step): the
// advected previous domain that decides the new mesh, and particle management that moves neither area nor
// momentum.
//
// The classic PFEM remesh (Idelsohn, Oñate & Del Pin 2004) re-detects the domain from the particles alone
// with the alpha shape; along a moving free surface elements appear and disappear from step to step, so the
// area (the mass: the particles' masses are their shares of the elements) changes, and a global correction
// that pushes it back pumps energy into the flow (cases/sloshing_free). Here, following Leyssens,
// Lambrechts & Remacle (UCLouvain; arXiv:2403.18416, 2024, and arXiv:2512.20347, 2025):
//  1. the last step's mesh, carried by the particles to their present positions, is the predicate of the
//     new domain (meshing::PreviousDomain): where the topology does not change, the domain does not change;
//     the alpha test only adds elements where two surfaces, or a surface and a wall, meet, and a separation
//     test tears off slivers (meshing/remesh.hpp, DomainDetection);
//  2. particles are managed on the advected mesh, before the new Delaunay triangulation:
//     - a fluid pair closer than remove_close_fraction h is merged into one particle carrying the pair's
//       mass-weighted velocity, acceleration and pressure (masses: the lumped areas sum_e A_e / 3, so
//       momentum is kept); inside the fluid it sits at the pair's centre of mass, on the free surface at
//       the position that keeps the area of the boundary polygon p-a-b-q (p, q the neighbours of the pair
//       along the boundary), and a pair with one surface particle keeps the surface particle's position; a
//       close pair that the advected mesh does not connect (two surfaces that meet) is merged too;
//     - a free-surface edge longer than split_edge_factor h gets a particle at its midpoint, and an element
//       larger than insert_area_factor h^2 one at its centroid, with the P1 interpolation of the state;
//       both lie on or inside the advected domain, which they therefore do not change.
//  3. what the remesh still changed is measured: the area and the kinetic energy of the same velocities on
//     the new mesh against the old (log.csv remesh_dA, remesh_dKE; totals in summary.json).
#include <lagfsi/geometry2d.hpp>

#include "point_grid.hpp"
#include "remesh_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace lagfsi::fluid {

RemeshPipeline::BoundaryChains RemeshPipeline::boundary_chains() const {
  // Boundary edges: used by one element, directed as in that element (counter-clockwise when it was made).
  const Index np = cloud_.n();
  BoundaryChains b;
  b.next.assign(np, -1);
  b.prev.assign(np, -1);
  b.pinched.assign(np, 0);
  for (const auto& [e, k] : mesh_.boundary_edges()) {
    const Index from = mesh_.tri[e][k], to = mesh_.tri[e][(k + 1) % 3];
    if (b.next[from] >= 0) b.pinched[from] = 1;
    if (b.prev[to] >= 0) b.pinched[to] = 1;
    b.next[from] = to;
    b.prev[to] = from;
  }
  return b;
}

meshing::PreviousDomain RemeshPipeline::advected_domain(const BoundaryChains& b) const {
  std::vector<std::array<Vec2, 3>> triangles;
  triangles.reserve(mesh_.tri.size());
  for (const auto& t : mesh_.tri) triangles.push_back({cloud_.pos(t[0]), cloud_.pos(t[1]), cloud_.pos(t[2])});
  std::vector<std::array<Vec2, 2>> boundary;
  for (Index i = 0; i < cloud_.n(); ++i)
    if (b.next[i] >= 0) boundary.push_back({cloud_.pos(i), cloud_.pos(b.next[i])});
  return meshing::PreviousDomain(std::move(triangles), std::move(boundary));
}

bool RemeshPipeline::manage_particles(const BoundaryChains& chain, std::vector<std::uint8_t>& meshed,
                                      std::vector<std::pair<Index, Index>>& boundary_edges,
                                      std::vector<std::pair<Index, Index>>* all_edges,
                                      const std::vector<char>& on_wall) {
  const Index np = cloud_.n();
  std::vector<Vec2> pts(np);
  for (Index i = 0; i < np; ++i) pts[i] = cloud_.pos(i);
  std::vector<double> lumped(np, 0.0);
  for (Index e = 0; e < static_cast<Index>(mesh_.tri.size()); ++e)
    for (Index i : mesh_.tri[e]) lumped[i] += std::abs(mesh_.element_area(cloud_.x(), e)) / 3.0;
  const auto on_boundary = [&](Index i) { return chain.next[i] >= 0 || chain.prev[i] >= 0; };

  std::vector<char> drop(np, 0), touched(np, 0);
  std::vector<Index> alias(np);  // a merged particle's survivor (itself otherwise)
  for (Index i = 0; i < np; ++i) alias[i] = i;
  std::vector<Index> heir(np, -1);  // a particle removed at a wall: the wall particle that stands for it
  // 1. Close pairs: merged. Pair (i, j): i survives with the pair's mass-weighted state; j goes.
  const auto walled = [&](Index i) { return on_wall.empty() ? 0 : int(on_wall[static_cast<size_t>(i)]); };
  const auto merge = [&](Index i, Index j) {
    // A particle on a wall ("wall_model": "constraints") survives where it is, the more constrained one of
    // two (a corner's particle keeps the corner); two on one wall meet at their centre of mass, on it.
    if (walled(j) > walled(i)) std::swap(i, j);
    const double wi = lumped[i], wj = lumped[j], w = wi + wj;
    const double si = w > 0 ? wi / w : 0.5, sj = 1.0 - si;
    Vec2 x = si * pts[i] + sj * pts[j];
    const bool bi = on_boundary(i), bj = on_boundary(j);
    if (walled(i) > walled(j) || walled(i) == 2) {
      x = pts[i];
    } else if (walled(i) == 1) {
      // both on a wall: their centre of mass, on the wall when it is one wall
    } else if (bi && !bj) {
      x = pts[i];
    } else if (bj && !bi) {
      x = pts[j];
    } else if (bi && bj) {
      // Along the boundary p -> a -> b -> q: m on the perpendicular of q - p through the midpoint, where the
      // polygon p-m-q has the area of p-a-b-q (cross(m, q - p) = cross(p, a) + cross(a, b) + cross(b, q)).
      Index a = -1, c = -1;
      if (chain.next[i] == j) a = i, c = j;
      if (chain.next[j] == i) a = j, c = i;
      x = 0.5 * (pts[i] + pts[j]);
      if (a >= 0 && !chain.pinched[a] && !chain.pinched[c]) {
        const Index p = chain.prev[a], q = chain.next[c];
        if (p >= 0 && q >= 0 && p != c && q != a && p != q) {
          const Vec2 d = pts[q] - pts[p];
          const double dn = d.norm();
          if (dn > 1e-12 * c_.h) {
            const double target = cross(pts[p], pts[a]) + cross(pts[a], pts[c]) + cross(pts[c], pts[q]);
            const double s = (target - cross(x, d)) / (-dn);
            if (std::abs(s) <= (pts[i] - pts[j]).norm() + 0.1 * c_.h) x += s * Vec2(-d.y(), d.x()) / dn;
          }
        }
      }
    }
    cloud_.x().segment<2>(2 * i) = x;
    cloud_.v().segment<2>(2 * i) = si * cloud_.v().segment<2>(2 * i) + sj * cloud_.v().segment<2>(2 * j);
    cloud_.a().segment<2>(2 * i) = si * cloud_.a().segment<2>(2 * i) + sj * cloud_.a().segment<2>(2 * j);
    cloud_.p()[i] = si * cloud_.p()[i] + sj * cloud_.p()[j];
    cloud_.owed()[i] += cloud_.owed()[j];
    drop[j] = touched[i] = touched[j] = 1;
    alias[j] = i;
    lumped[i] = w;  // a survivor merged again (a third particle on a corner) weighs the pair
    ++merged_;
  };
  // A fluid particle f removed at a wall or ghost particle g: g stands for it, and takes its share of the area
  // and what it was owed.
  const auto leave_to = [&](Index f, Index g) {
    drop[f] = touched[f] = 1;
    heir[f] = g;
    cloud_.owed()[g] += cloud_.owed()[f];
    ++wall_removed_;
  };
  if (!on_wall.empty()) {
    // Walls as constraints: a particle put on a wall (FluidWalls::snap_to_walls) may land on or next to a
    // particle already there that the previous mesh does not connect it to (a drop sliding into a corner
    // lands on the corner's particle): such pairs are merged too. Both may be out of the mesh (no mass):
    // the merge then takes the mean state.
    // A fluid particle put on a wall's end where a structure stands (its ghost particle: the foot of an
    // obstacle in a gap of the floor, a gate's hinge) goes, as one pressed against a wall particle below.
    const double r = std::max(s_.close_fraction, 0.05) * c_.h;
    // Each grid sized for what it will hold (a table is zeroed at every remesh): the fluid particles, and the
    // wall and ghost particles (none with walls as constraints but a structure's ghosts).
    const auto n_fluid =
        static_cast<std::size_t>(std::count(cloud_.kind().begin(), cloud_.kind().end(), ParticleKind::Fluid));
    PointGrid grid(std::max(r, 1e-300), n_fluid),
        prescribed(std::max(r, 1e-300), static_cast<std::size_t>(np) - n_fluid);
    for (Index i = 0; i < np; ++i)
      if (cloud_.kind(i) != ParticleKind::Fluid) prescribed.add(pts[i], i);
    for (Index i = 0; i < np; ++i) {
      if (cloud_.kind(i) != ParticleKind::Fluid) continue;
      if (const Index g = prescribed.find(pts[i], r, pts); g >= 0) {
        leave_to(i, g);
        continue;
      }
      // A third particle put on the same corner in one step merges with the pair's survivor (the corner's
      // particle; it was left beside it, and the triangulation failed on the duplicate point).
      const Index j = grid.find(pts[i], r, pts);
      if (j >= 0 && !drop[j] && (walled(i) > 0 || walled(j) > 0)) {
        merge(j, i);
        if (drop[j]) grid.add(pts[i], i);  // i survived (the more constrained): the later find returns it
      } else {
        grid.add(pts[i], i);
      }
    }
  }
  if (s_.close_fraction > 0) {
    // A fluid particle pressed against a wall particle: inside the fluid it goes (the wall stands for it;
    // the domain does not change); on the free surface (where the surface meets the wall) it is merged with
    // its fluid neighbour along the surface, which keeps the boundary's area. Against a structure's face the
    // distance is to the face's segments, not only to its ghost particles: the Delaunay mesh does not keep
    // a face segment as an edge, and a surface particle drifting onto the face midway between two ghosts
    // (1.6 mm from each at h = 3.3 mm) was joined to them by two triangles that stay valid as it crosses,
    // and went into the plate (flexible_tank under generalized-alpha, rho_inf = 0.8 and 0.9, at 0.57 s).
    const double r_close = s_.close_fraction * c_.h;
    const auto pressed = [&](Index f, Index g) {
      if ((pts[f] - pts[g]).norm() < r_close) return true;
      for (Index q : ghosts_.face_neighbours(g))
        if (segment_distance(pts[f], pts[g], pts[q]) < r_close) return true;
      return false;
    };
    for (const auto& t : mesh_.tri)
      for (int k = 0; k < 3; ++k) {
        const Index a = t[k], c = t[(k + 1) % 3];
        const bool fa = cloud_.kind(a) == ParticleKind::Fluid, fc = cloud_.kind(c) == ParticleKind::Fluid;
        if (fa == fc) continue;
        const Index f = fa ? a : c;
        if (touched[f] || !pressed(f, f == a ? c : a)) continue;
        Index partner = -1;
        if (on_boundary(f))
          for (Index q : {chain.next[f], chain.prev[f]})
            if (partner < 0 && q >= 0 && cloud_.kind(q) == ParticleKind::Fluid && !touched[q]) partner = q;
        if (partner >= 0) {
          merge(partner, f);
          ++wall_removed_;
        } else {
          leave_to(f, f == a ? c : a);
        }
      }
    for (const auto& [i, j] : meshing::close_fluid_pairs(pts, cloud_.kind(), cloud_.h(), mesh_.tri, s_.close_fraction))
      if (!touched[i] && !touched[j]) merge(i, j);
    // Two surfaces that meet (a film landing on the pool, two jets crossing, two drops): a pair closer than
    // close_fraction h that the previous mesh does not connect. Its edges do not see the pair; the new
    // triangulation joins it by a sliver whose particles pass each other within the step (dam_break_obstacle:
    // two film particles 0.03 h apart at 3 m/s against each other, a sliver turned over at every step down to
    // dt/16). Merged too, as the alpha detection merges close pairs on the new mesh.
    const double r_meet = s_.close_fraction * c_.h;
    PointGrid untouched(r_meet, static_cast<std::size_t>(np));
    for (Index i = 0; i < np; ++i) {
      if (cloud_.kind(i) != ParticleKind::Fluid || touched[i]) continue;
      const Index j = untouched.find(pts[i], r_meet, pts);
      if (j >= 0 && !touched[j]) {
        merge(j, i);
        ++merged_meeting_;
      } else {
        untouched.add(pts[i], i);
      }
    }
  }

  // 2. Refinement where the particles moved apart (none next to a particle that was just merged or removed:
  // its elements are gone).
  struct NewParticle {
    Vec2 x, v, a;
    double p, h;
  };
  std::vector<NewParticle> fresh;
  std::vector<Index> split_at(np, -1);  // boundary edge from a (to chain.next[a]) split by new particle k
  // Walls as constraints: many particles lie on one line (a floor), and one outside the mesh (just let go,
  // or landed) may sit on a boundary edge between two others: no new particle within close_fraction h of an
  // existing one.
  std::unique_ptr<PointGrid> taken;
  const double r_taken = std::max(s_.close_fraction, 0.05) * c_.h;
  if (!on_wall.empty()) {
    taken = std::make_unique<PointGrid>(r_taken, static_cast<std::size_t>(np));
    for (Index i = 0; i < np; ++i)
      if (!drop[i]) taken->add(pts[i], i);
  }
  std::vector<Vec2> taken_pts = taken ? pts : std::vector<Vec2>();
  const auto free_spot = [&](const Vec2& x) {
    if (!taken) return true;
    if (taken->find(x, r_taken, taken_pts) >= 0) return false;
    taken->add(x, static_cast<Index>(taken_pts.size()));
    taken_pts.push_back(x);
    return true;
  };
  const auto between = [&](const std::vector<Index>& ids, const std::vector<double>& w) {
    NewParticle q{Vec2::Zero(), Vec2::Zero(), Vec2::Zero(), 0.0, 0.0};
    for (size_t k = 0; k < ids.size(); ++k) {
      q.x += w[k] * pts[ids[k]];
      q.v += w[k] * cloud_.v().segment<2>(2 * ids[k]);
      q.a += w[k] * cloud_.a().segment<2>(2 * ids[k]);
      q.p += w[k] * cloud_.p()[ids[k]];
      q.h += w[k] * cloud_.h(ids[k]);
    }
    return q;
  };
  if (s_.split_factor > 0)
    for (Index a = 0; a < np; ++a) {
      const Index c = chain.next[a];
      if (c < 0 || touched[a] || touched[c]) continue;
      if (cloud_.kind(a) != ParticleKind::Fluid && cloud_.kind(c) != ParticleKind::Fluid) continue;
      const double he = 0.5 * (cloud_.h(a) + cloud_.h(c));
      if ((pts[a] - pts[c]).norm() > s_.split_factor * he) {
        const NewParticle q = between({a, c}, {0.5, 0.5});
        if (!free_spot(q.x)) continue;
        split_at[a] = np + static_cast<Index>(fresh.size());
        fresh.push_back(q);
        ++split_;
      }
    }
  if (s_.insert_factor > 0)
    for (Index e : meshing::oversized_elements(pts, cloud_.h(), mesh_.tri, s_.insert_factor)) {
      const auto& t = mesh_.tri[e];
      if (touched[t[0]] || touched[t[1]] || touched[t[2]] || !(mesh_.element_area(cloud_.x(), e) > 0)) continue;
      const NewParticle q = between({t[0], t[1], t[2]}, {1.0 / 3, 1.0 / 3, 1.0 / 3});
      if (!free_spot(q.x)) continue;
      fresh.push_back(q);
      ++inserted_;
    }
  // A merged particle's final survivor (a survivor may have been merged again at a corner).
  for (Index i = 0; i < np; ++i)
    while (alias[alias[i]] != alias[i]) alias[i] = alias[alias[i]];
  // The previous mesh's topology through the changes: boundary edges follow merges (to the survivor) and
  // splits (two halves); those of a removed particle go.
  std::vector<std::uint8_t> used(np + fresh.size(), 0);
  for (const auto& t : mesh_.tri)
    for (Index i : t) used[i] = 1;
  std::vector<std::pair<Index, Index>> edges;
  for (Index a = 0; a < np; ++a) {
    const Index c = chain.next[a];
    if (c < 0 || (drop[a] && alias[a] == a) || (drop[c] && alias[c] == c)) continue;
    const Index a2 = alias[a], c2 = alias[c];
    if (a2 == c2) continue;
    if (split_at[a] >= 0) {
      edges.emplace_back(a2, split_at[a]);
      edges.emplace_back(split_at[a], c2);
    } else {
      edges.emplace_back(a2, c2);
    }
  }
  std::vector<std::pair<Index, Index>> interior;
  if (all_edges != nullptr) {
    // Every edge of the previous mesh through the merges (boundary edges, with their splits, are in `edges`).
    for (const auto& t : mesh_.tri)
      for (int k = 0; k < 3; ++k) {
        const Index a = t[k], c = t[(k + 1) % 3];
        if ((drop[a] && alias[a] == a) || (drop[c] && alias[c] == c)) continue;
        const Index a2 = alias[a], c2 = alias[c];
        if (a2 != c2 && chain.next[a] != c && chain.next[c] != a) interior.emplace_back(a2, c2);
      }
  }
  for (const auto& q : fresh) append_particle(q.x, q.v, q.a, q.p, q.h);
  drop.resize(static_cast<size_t>(cloud_.n()), 0);
  const bool dropped = drop_particles(drop);
  const auto to_new = [&](Index i) { return dropped ? renumber_[i] : i; };
  survivor_.assign(static_cast<size_t>(np), -1);
  for (Index i = 0; i < np; ++i)
    if (!(drop[i] && alias[i] == i))
      survivor_[i] = to_new(alias[i]);
    else if (heir[i] >= 0)
      survivor_[i] = to_new(heir[i]);
  meshed.assign(static_cast<size_t>(cloud_.n()), 0);
  for (Index i = 0; i < static_cast<Index>(used.size()); ++i) {
    const Index k = to_new(i);
    if (k >= 0) meshed[k] = used[i] || cloud_.kind(k) == ParticleKind::Fluid;
  }
  boundary_edges.clear();
  for (const auto& [a, c] : edges)
    if (to_new(a) >= 0 && to_new(c) >= 0) boundary_edges.emplace_back(to_new(a), to_new(c));
  if (all_edges != nullptr) {
    *all_edges = boundary_edges;
    for (const auto& [a, c] : interior)
      if (to_new(a) >= 0 && to_new(c) >= 0) all_edges->emplace_back(to_new(a), to_new(c));
  }
  return dropped || !fresh.empty();
}

}  // namespace lagfsi::fluid
