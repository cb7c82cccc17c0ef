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

#include "particle_management.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

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

RemeshPipeline::AdvectedDomain RemeshPipeline::advected_domain(const BoundaryChains& b) const {
  std::vector<std::array<Vec2, 3>> triangles;
  triangles.reserve(mesh_.tri.size());
  for (const auto& t : mesh_.tri) triangles.push_back({cloud_.pos(t[0]), cloud_.pos(t[1]), cloud_.pos(t[2])});
  triangles.insert(triangles.end(), open_regions_.begin(), open_regions_.end());  // an inflow's strip
  for (const auto& t : wet_corners_) triangles.push_back({cloud_.pos(t[0]), cloud_.pos(t[1]), cloud_.pos(t[2])});
  std::vector<std::array<Vec2, 2>> boundary;
  for (Index i = 0; i < cloud_.n(); ++i)
    if (b.next[i] >= 0) boundary.push_back({cloud_.pos(i), cloud_.pos(b.next[i])});
  return {std::move(triangles), std::move(boundary)};
}

bool RemeshPipeline::manage_particles(const BoundaryChains& chain, std::vector<std::uint8_t>& meshed,
                                      std::vector<std::pair<Index, Index>>& boundary_edges,
                                      std::vector<std::pair<Index, Index>>* all_edges,
                                      const std::vector<char>& on_wall) {
  Management m = start_management(chain, on_wall);
  // 1. Close pairs: merged. Pair (i, j): i survives with the pair's mass-weighted state; j goes.
  if (!on_wall.empty()) merge_onto_walls(m);
  if (s_.close_fraction > 0) {
    merge_pressed_against_walls(m);
    merge_close_pairs(m);
  }
  if (size_.adaptive()) coarsen(m);
  // 2. Refinement where the particles moved apart (none next to a particle that was just merged or removed:
  // its elements are gone).
  std::vector<Index> split_from;
  std::vector<NewParticle> splits, inserts;
  if (s_.split_factor > 0) splits = split_long_edges(m, split_from);
  if (s_.insert_factor > 0) inserts = insert_in_large_elements(m);
  if (!on_wall.empty()) m.occupy_spots(std::max(s_.close_fraction, 0.05), cloud_.h_max(), {&splits, &inserts});
  for (size_t k = 0; k < splits.size(); ++k)
    if (m.free_spot(splits[k].x, splits[k].h)) {
      m.split_at[split_from[k]] = m.np + static_cast<Index>(m.fresh.size());
      m.fresh.push_back(splits[k]);
      ++split_;
    }
  for (const NewParticle& q : inserts)
    if (m.free_spot(q.x, q.h)) {
      m.fresh.push_back(q);
      ++inserted_;
    }
  // 3. The previous mesh's topology through the changes, then the changes made to the cloud.
  carry_topology(m, all_edges != nullptr);
  return apply_management(m, meshed, boundary_edges, all_edges);
}

RemeshPipeline::Management RemeshPipeline::start_management(const BoundaryChains& chain,
                                                            const std::vector<char>& on_wall) const {
  // The positions and the lumped masses of the advected mesh; no particle touched yet.
  Management m(chain, on_wall);
  const Index np = m.np = cloud_.n();
  m.pts.resize(np);
  for (Index i = 0; i < np; ++i) m.pts[i] = cloud_.pos(i);
  m.lumped.assign(np, 0.0);
  for (Index e = 0; e < static_cast<Index>(mesh_.tri.size()); ++e)
    for (Index i : mesh_.tri[e]) m.lumped[i] += std::abs(mesh_.element_area(cloud_.x(), e)) / 3.0;
  m.drop.assign(np, 0);
  m.touched.assign(np, 0);
  m.alias.resize(np);
  for (Index i = 0; i < np; ++i) m.alias[i] = i;
  m.heir.assign(np, -1);
  m.split_at.assign(np, -1);
  if (mpi_run::size() > 1) m.part = std::make_unique<meshing::SpacePartition>(m.pts, mpi_run::size());
  return m;
}

void RemeshPipeline::merge_pair(Management& m, Index i, Index j) {
  const std::vector<Vec2>& pts = m.pts;
  const BoundaryChains& chain = m.chain;
  // A particle on a wall ("wall_model": "constraints") survives where it is, the more constrained one of
  // two (a corner's particle keeps the corner); two on one wall meet at their centre of mass, on it.
  if (m.walled(j) > m.walled(i)) std::swap(i, j);
  const double wi = m.lumped[i], wj = m.lumped[j], w = wi + wj;
  const double si = w > 0 ? wi / w : 0.5, sj = 1.0 - si;
  Vec2 x = si * pts[i] + sj * pts[j];
  const bool bi = m.on_boundary(i), bj = m.on_boundary(j);
  if (m.walled(i) > m.walled(j) || m.walled(i) == 2) {
    x = pts[i];
  } else if (m.walled(i) == 1) {
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
        const double he = 0.5 * (cloud_.h(i) + cloud_.h(j));
        if (dn > 1e-12 * he) {
          const double target = cross(pts[p], pts[a]) + cross(pts[a], pts[c]) + cross(pts[c], pts[q]);
          const double s = (target - cross(x, d)) / (-dn);
          if (std::abs(s) <= (pts[i] - pts[j]).norm() + 0.1 * he) x += s * Vec2(-d.y(), d.x()) / dn;
        }
      }
    }
  }
  cloud_.x().segment<2>(2 * i) = x;
  cloud_.v().segment<2>(2 * i) = si * cloud_.v().segment<2>(2 * i) + sj * cloud_.v().segment<2>(2 * j);
  cloud_.a().segment<2>(2 * i) = si * cloud_.a().segment<2>(2 * i) + sj * cloud_.a().segment<2>(2 * j);
  cloud_.p()[i] = si * cloud_.p()[i] + sj * cloud_.p()[j];
  cloud_.owed()[i] += cloud_.owed()[j];
  m.drop[j] = m.touched[i] = m.touched[j] = 1;
  m.alias[j] = i;
  m.lumped[i] = w;  // a survivor merged again (a third particle on a corner) weighs the pair
  ++merged_;
}

void RemeshPipeline::leave_to_wall(Management& m, Index f, Index g) {
  // A fluid particle f removed at a wall or ghost particle g: g stands for it, and takes its share of the area
  // and what it was owed.
  m.drop[f] = m.touched[f] = 1;
  m.heir[f] = g;
  cloud_.owed()[g] += cloud_.owed()[f];
  ++wall_removed_;
}

void RemeshPipeline::merge_onto_walls(Management& m) {
  // Walls as constraints: a particle put on a wall (FluidWalls::snap_to_walls) may land on or next to a
  // particle already there that the previous mesh does not connect it to (a drop sliding into a corner
  // lands on the corner's particle): such pairs are merged too. Both may be out of the mesh (no mass):
  // the merge then takes the mean state.
  // A fluid particle put on a wall's end where a structure stands (its ghost particle: the foot of an
  // obstacle in a gap of the floor, a gate's hinge) goes, as one pressed against a wall particle below.
  const Index np = m.np;
  const std::vector<Vec2>& pts = m.pts;
  // Within r h_i of fluid particle i (h_i its size); the grids' cells r h_max.
  const double r = std::max(s_.close_fraction, 0.05), cell = std::max(r * cloud_.h_max(), 1e-300);
  const auto fluid = [&](Index i) { return cloud_.kind(i) == ParticleKind::Fluid; };
  // The fluid particles on walls, and the wall and ghost particles (none with walls as constraints but a structure's
  // ghosts), each grid sized for what it will hold (a table is zeroed at every remesh).
  std::size_t n_walled = 0;
  for (Index i = 0; i < np; ++i) n_walled += fluid(i) && m.walled(i) > 0;
  PointGrid on_walls(2.0 * cell, n_walled);
  for (Index i = 0; i < np; ++i)
    if (fluid(i) && m.walled(i) > 0) on_walls.add(pts[i], i);
  const auto n_fluid =
      static_cast<std::size_t>(std::count(cloud_.kind().begin(), cloud_.kind().end(), ParticleKind::Fluid));
  PointGrid prescribed(cell, static_cast<std::size_t>(np) - n_fluid);
  for (Index i = 0; i < np; ++i)
    if (!fluid(i)) prescribed.add(pts[i], i);
  // What each fluid particle may do, which the others do not change: go, for a wall or ghost particle g within
  // r h_i (the pair (i, g)); or, near a particle on a wall, merge with one (the pair (i, -1)). A merge needs a
  // particle on a wall in the pair, within r h_max of the other, and what a particle's search finds is decided by
  // the particles within r h_max of it: so only the particles within 2 r h_max of a particle on a wall take part
  // (the same merges as a pass over all of them). An MPI run: each process finds its own particles' pairs, and
  // every process takes all of them in particle order, as one process does.
  std::vector<Index> acts;
  for (Index i = 0; i < np; ++i) {
    if (!fluid(i) || !m.mine(i)) continue;
    if (const Index g = prescribed.find(pts[i], r * cloud_.h(i), pts); g >= 0)
      acts.insert(acts.end(), {i, g});
    else if (n_walled > 0 && (m.walled(i) > 0 || on_walls.find(pts[i], 2.0 * cell, pts) >= 0))
      acts.insert(acts.end(), {i, -1});
  }
  if (m.part) acts = gather_pairs_in_order(acts);
  std::size_t n_near = 0;
  for (size_t k = 1; k < acts.size(); k += 2) n_near += acts[k] < 0;
  PointGrid grid(cell, n_near);
  for (size_t k = 0; k + 1 < acts.size(); k += 2) {
    const Index i = acts[k];
    if (acts[k + 1] >= 0) {
      leave_to_wall(m, i, acts[k + 1]);
      continue;
    }
    // A third particle put on the same corner in one step merges with the pair's survivor (the corner's
    // particle; it was left beside it, and the triangulation failed on the duplicate point).
    const Index j = grid.find(pts[i], r * cloud_.h(i), pts);
    if (j >= 0 && !m.drop[j] && (m.walled(i) > 0 || m.walled(j) > 0)) {
      merge_pair(m, j, i);
      if (m.drop[j]) grid.add(pts[i], i);  // i survived (the more constrained): the later find returns it
    } else {
      grid.add(pts[i], i);
    }
  }
}

void RemeshPipeline::merge_pressed_against_walls(Management& m) {
  // A fluid particle pressed against a wall particle: inside the fluid it goes (the wall stands for it;
  // the domain does not change); on the free surface (where the surface meets the wall) it is merged with
  // its fluid neighbour along the surface, which keeps the boundary's area. Against a structure's face the
  // distance is to the face's segments, not only to its ghost particles: the Delaunay mesh does not keep
  // a face segment as an edge, and a surface particle drifting onto the face midway between two ghosts (each
  // half a spacing away) was joined to them by two triangles that stay valid as it crosses, and went into the
  // structure (the plate of cases/flexible_tank). The same holds for a wall's particles: a particle pressed onto
  // the edge between two wall particles of its element that runs along a wall (its midpoint on the wall's line, not
  // the long side of a corner's triangle) goes as well. Its element was removed as flat, which made the particle a
  // free surface with p = 0 inside the water, and a wake's suction opened a crack from it (Turek & Hron's cylinder
  // with graded particles).
  const std::vector<Vec2>& pts = m.pts;
  const auto pressed = [&](Index f, Index g, Index third) {
    const double r_close = s_.close_fraction * cloud_.h(f);
    if ((pts[f] - pts[g]).norm() < r_close) return true;
    if (wall_depth_ && cloud_.kind(g) == ParticleKind::Wall && cloud_.kind(third) == ParticleKind::Wall &&
        segment_distance(pts[f], pts[g], pts[third]) < r_close &&
        std::abs(wall_depth_(0.5 * (pts[g] + pts[third]), t_remesh_)) < 1e-3 * cloud_.h(f))
      return true;
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
      if (m.touched[f] || !pressed(f, f == a ? c : a, t[(k + 2) % 3])) continue;
      Index partner = -1;
      if (m.on_boundary(f))
        for (Index q : {m.chain.next[f], m.chain.prev[f]})
          if (partner < 0 && q >= 0 && cloud_.kind(q) == ParticleKind::Fluid && !m.touched[q]) partner = q;
      if (partner >= 0) {
        merge_pair(m, partner, f);
        ++wall_removed_;
      } else {
        leave_to_wall(m, f, f == a ? c : a);
      }
    }
}

void RemeshPipeline::merge_close_pairs(Management& m) {
  // The fluid pairs of the advected mesh closer than close_fraction h (meshing::close_fluid_pairs).
  for (const auto& [i, j] : meshing::close_fluid_pairs(m.pts, cloud_.kind(), cloud_.h(), mesh_.tri, s_.close_fraction))
    if (!m.touched[i] && !m.touched[j]) merge_pair(m, i, j);
  // Two surfaces that meet (a film landing on the pool, two jets crossing, two drops): a pair closer than
  // close_fraction h that the previous mesh does not connect. Its edges do not see the pair; the new
  // triangulation joins it by a sliver whose particles pass each other within the step (cases/dam_break_obstacle:
  // two film particles running into each other, a sliver turned over at every step). Merged too, as the alpha
  // detection merges close pairs on the new mesh.
  // Cells of the smallest particle size (at least close_fraction h_max, as find() needs): about a particle per
  // cell where the particles are finest, so that a search reads a few cache lines, not nine mostly empty slots of a
  // table of a slot per particle (the same pairs whatever the cell: find() returns the largest id in reach).
  const double cell = std::max({s_.close_fraction * cloud_.h_max(), cloud_.h_min(), 1e-300});
  const auto meet = [&](Index i, PointGrid& untouched) {
    if (cloud_.kind(i) != ParticleKind::Fluid || m.touched[i]) return;
    const Index j = untouched.find(m.pts[i], s_.close_fraction * cloud_.h(i), m.pts);
    if (j >= 0 && !m.touched[j]) {
      merge_pair(m, j, i);
      ++merged_meeting_;
    } else {
      untouched.add(m.pts[i], i);
    }
  };
  if (!m.part) {
    PointGrid untouched(cell, static_cast<std::size_t>(m.np));
    for (Index i = 0; i < m.np; ++i) meet(i, untouched);
    return;
  }
  // An MPI run: the same pass over the particles that have another within reach (meeting_candidates), the only ones
  // whose searches find anything.
  const std::vector<Index> ids = meeting_candidates(m, cell);
  PointGrid untouched(cell, ids.size());
  for (Index i : ids) meet(i, untouched);
}

void RemeshPipeline::follow_size_field(const BoundaryChains& chain, const std::vector<char>& on_wall, double t) {
  const Index np = cloud_.n();
  std::vector<char> source(static_cast<size_t>(np), 0);
  for (Index i = 0; i < np; ++i)
    source[i] = !cloud_.is_fluid(i) || chain.next[i] >= 0 || chain.prev[i] >= 0 ||
                (!on_wall.empty() && on_wall[static_cast<size_t>(i)] != 0);
  apply_size_field(source, t);
}

void RemeshPipeline::apply_size_field(std::vector<char>& source, double t) {
  const Index np = cloud_.n();
  const std::vector<Vec2> pts = cloud_.positions();
  if (size_.strain_rate() > 0) {  // the flow indicator: where the flow strains fast, as at a surface
    std::vector<Vec2> v(static_cast<size_t>(np));
    for (Index i = 0; i < np; ++i) v[static_cast<size_t>(i)] = cloud_.vel(i);
    size_.mark_straining(pts, v, mesh_.tri, source);
  }
  std::vector<double> h;
  size_.targets(pts, mesh_.tri, source, t, h);
  for (Index i = 0; i < np; ++i)
    if (cloud_.is_fluid(i)) cloud_.set_h(i, h[static_cast<size_t>(i)]);
}

std::vector<std::pair<Index, Index>> RemeshPipeline::coarsen_pairs(const std::vector<Vec2>& pts,
                                                                   const std::function<bool(Index)>& interior) const {
  // Equilibrium of the management: edges between kCoarsenFraction h and about 1.5 h (an element larger than
  // insert_area_factor h^2 gets a particle).
  constexpr double kCoarsenFraction = 0.6;
  std::vector<std::tuple<double, Index, Index>> pairs;
  for (const auto& t : mesh_.tri)
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k], c = t[(k + 1) % 3];
      if (a > c || !interior(a) || !interior(c)) continue;  // each interior edge once (it has two elements)
      const double ratio = (pts[a] - pts[c]).norm() / (0.5 * (cloud_.h(a) + cloud_.h(c)));
      if (ratio < kCoarsenFraction) pairs.emplace_back(ratio, a, c);
    }
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::pair<Index, Index>> out;
  out.reserve(pairs.size());
  for (const auto& [ratio, a, c] : pairs) out.emplace_back(a, c);
  return out;
}

void RemeshPipeline::coarsen(Management& m) {
  // An adaptive size field: two interior fluid particles joined by an edge of the advected mesh and closer than
  // kCoarsenFraction times their mean size are merged (merge_pair: mass-weighted state at their centre of mass,
  // so neither the domain, nor the area, nor the momentum changes), the closest pairs (relative to their size)
  // first, each particle at most once a remesh; the insertion in oversized elements refines where the size falls.
  const auto interior = [&](Index i) { return cloud_.is_fluid(i) && !m.on_boundary(i) && m.walled(i) == 0; };
  for (const auto& [a, c] : coarsen_pairs(m.pts, interior))
    if (!m.touched[a] && !m.touched[c]) {
      merge_pair(m, a, c);
      ++coarsened_;
    }
}

bool RemeshPipeline::follow_size_field_alpha(double t) {
  // The sources: the free surface, the particles of elements with a wall's or a structure's particle (the wet faces)
  // and, through SizeField::targets, the particles in no element.
  const Index np = cloud_.n();
  std::vector<char> source(static_cast<size_t>(np), 0), beside(static_cast<size_t>(np), 0);
  for (const auto& e : mesh_.tri)
    if (!cloud_.is_fluid(e[0]) || !cloud_.is_fluid(e[1]) || !cloud_.is_fluid(e[2]))
      for (Index i : e) beside[static_cast<size_t>(i)] = 1;
  for (Index i = 0; i < np; ++i)
    source[i] = !cloud_.is_fluid(i) || beside[i] || (static_cast<size_t>(i) < mesh_.free.size() && mesh_.free[i]);
  apply_size_field(source, t);
  const std::vector<Vec2> pts = cloud_.positions();
  // Interior pairs closer than their size merge into the survivor at their centre of mass with their momentum (the
  // lumped shares of the mesh as masses); the alpha shape of the new cloud then sets the domain, as at every remesh.
  const std::vector<double> mass = mesh_.nodal_areas(cloud_.x(), np);
  const auto interior = [&](Index i) { return cloud_.is_fluid(i) && !source[static_cast<size_t>(i)]; };
  std::vector<char> drop(static_cast<size_t>(np), 0), touched(static_cast<size_t>(np), 0);
  Vec& x = cloud_.x();
  Vec& v = cloud_.v();
  Vec& a = cloud_.a();
  Vec& p = cloud_.p();
  for (const auto& [i, j] : coarsen_pairs(pts, interior)) {
    if (touched[i] || touched[j]) continue;
    touched[i] = touched[j] = 1;
    const double w = mass[i] + mass[j], si = w > 0 ? mass[i] / w : 0.5, sj = 1.0 - si;
    x.segment<2>(2 * i) = si * x.segment<2>(2 * i) + sj * x.segment<2>(2 * j);
    v.segment<2>(2 * i) = si * v.segment<2>(2 * i) + sj * v.segment<2>(2 * j);
    a.segment<2>(2 * i) = si * a.segment<2>(2 * i) + sj * a.segment<2>(2 * j);
    p[i] = si * p[i] + sj * p[j];
    cloud_.set_h(i, std::max(cloud_.h(i), cloud_.h(j)));
    drop[static_cast<size_t>(j)] = 1;
    ++coarsened_;
  }
  return drop_particles(drop);
}

std::vector<RemeshPipeline::NewParticle> RemeshPipeline::split_long_edges(const Management& m,
                                                                          std::vector<Index>& from) const {
  // A boundary edge with a fluid end longer than split_edge_factor h_e (h_e the mean of its ends' h) gets a
  // particle at its midpoint, with the mean state of its ends.
  std::vector<NewParticle> q;
  from.clear();
  for (Index a = 0; a < m.np; ++a) {
    const Index c = m.chain.next[a];
    if (c < 0 || m.touched[a] || m.touched[c]) continue;
    if (cloud_.kind(a) != ParticleKind::Fluid && cloud_.kind(c) != ParticleKind::Fluid) continue;
    const double he = 0.5 * (cloud_.h(a) + cloud_.h(c));
    if ((m.pts[a] - m.pts[c]).norm() > s_.split_factor * he) {
      q.push_back(m.between(cloud_, {a, c}, {0.5, 0.5}));
      from.push_back(a);
    }
  }
  return q;
}

std::vector<RemeshPipeline::NewParticle> RemeshPipeline::insert_in_large_elements(const Management& m) const {
  // An element larger than insert_area_factor h_e^2 (meshing::oversized_elements) gets a particle at its
  // centroid, with the P1 interpolation of the state there.
  std::vector<NewParticle> q;
  for (Index e : meshing::oversized_elements(m.pts, cloud_.h(), mesh_.tri, s_.insert_factor)) {
    const auto& t = mesh_.tri[e];
    if (m.touched[t[0]] || m.touched[t[1]] || m.touched[t[2]] || !(mesh_.element_area(cloud_.x(), e) > 0)) continue;
    q.push_back(m.between(cloud_, {t[0], t[1], t[2]}, {1.0 / 3, 1.0 / 3, 1.0 / 3}));
  }
  return q;
}

void RemeshPipeline::carry_topology(Management& m, bool all_edges) const {
  const Index np = m.np;
  std::vector<Index>& alias = m.alias;
  const std::vector<char>& drop = m.drop;
  // A merged particle's final survivor (a survivor may have been merged again at a corner).
  for (Index i = 0; i < np; ++i)
    while (alias[alias[i]] != alias[i]) alias[i] = alias[alias[i]];
  // The previous mesh's topology through the changes: boundary edges follow merges (to the survivor) and
  // splits (two halves); those of a removed particle go.
  m.used.assign(np + m.fresh.size(), 0);
  for (const auto& t : mesh_.tri)
    for (Index i : t) m.used[i] = 1;
  for (Index a = 0; a < np; ++a) {
    const Index c = m.chain.next[a];
    if (c < 0 || (drop[a] && alias[a] == a) || (drop[c] && alias[c] == c)) continue;
    const Index a2 = alias[a], c2 = alias[c];
    if (a2 == c2) continue;
    if (m.split_at[a] >= 0) {
      m.edges.emplace_back(a2, m.split_at[a]);
      m.edges.emplace_back(m.split_at[a], c2);
    } else {
      m.edges.emplace_back(a2, c2);
    }
  }
  if (all_edges) {
    // Every edge of the previous mesh through the merges (boundary edges, with their splits, are in `edges`).
    for (const auto& t : mesh_.tri)
      for (int k = 0; k < 3; ++k) {
        const Index a = t[k], c = t[(k + 1) % 3];
        if ((drop[a] && alias[a] == a) || (drop[c] && alias[c] == c)) continue;
        const Index a2 = alias[a], c2 = alias[c];
        if (a2 != c2 && m.chain.next[a] != c && m.chain.next[c] != a) m.interior.emplace_back(a2, c2);
      }
  }
}

bool RemeshPipeline::apply_management(Management& m, std::vector<std::uint8_t>& meshed,
                                      std::vector<std::pair<Index, Index>>& boundary_edges,
                                      std::vector<std::pair<Index, Index>>* all_edges) {
  // The new particles are appended, the removed ones dropped (drop_particles renumbers the rest); survivor_,
  // `meshed` and the edges are then given in the new numbering.
  const Index np = m.np;
  const std::vector<Index>& alias = m.alias;
  std::vector<char>& drop = m.drop;
  for (const auto& q : m.fresh) append_particle(q.x, q.v, q.a, q.p, q.h);
  drop.resize(static_cast<size_t>(cloud_.n()), 0);
  const bool dropped = drop_particles(drop);
  const auto to_new = [&](Index i) { return dropped ? renumber_[i] : i; };
  survivor_.assign(static_cast<size_t>(np), -1);
  for (Index i = 0; i < np; ++i)
    if (!(drop[i] && alias[i] == i))
      survivor_[i] = to_new(alias[i]);
    else if (m.heir[i] >= 0)
      survivor_[i] = to_new(m.heir[i]);
  meshed.assign(static_cast<size_t>(cloud_.n()), 0);
  for (Index i = 0; i < static_cast<Index>(m.used.size()); ++i) {
    const Index k = to_new(i);
    if (k >= 0) meshed[k] = m.used[i] || cloud_.kind(k) == ParticleKind::Fluid;
  }
  boundary_edges.clear();
  for (const auto& [a, c] : m.edges)
    if (to_new(a) >= 0 && to_new(c) >= 0) boundary_edges.emplace_back(to_new(a), to_new(c));
  if (all_edges != nullptr) {
    *all_edges = boundary_edges;
    for (const auto& [a, c] : m.interior)
      if (to_new(a) >= 0 && to_new(c) >= 0) all_edges->emplace_back(to_new(a), to_new(c));
  }
  return dropped || !m.fresh.empty();
}

}  // namespace lagfsi::fluid
