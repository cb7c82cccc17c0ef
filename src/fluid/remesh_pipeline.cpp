// The PFEM remeshing of a step and its filters (remesh_pipeline.hpp).
#include "remesh_pipeline.hpp"

#include <lagfsi/mpi_run.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

namespace lagfsi::fluid {

namespace {

/// A new fluid particle at x with the given state; its reference position is where it is created.
ParticleCloud::Particle fluid_particle(const Vec2& x, const Vec2& v, const Vec2& a, double p, double h) {
  ParticleCloud::Particle q;
  q.kind = ParticleKind::Fluid;
  q.h = h;
  q.x = x;
  q.X0 = x;
  q.v = v;
  q.a = a;
  q.p = p;
  return q;
}

/// Keeps the triangles whose bounding box meets the part's box grown by `halo` (a hair more), and at least one: an
/// empty previous domain would change the detection (RemeshPipeline::remesh_now), and a triangle that meets no point
/// the part asks about changes no answer.
void keep_near_part(std::vector<std::array<Vec2, 3>>& triangles, const meshing::SpacePartition& partition,
                    double halo) {
  if (triangles.empty()) return;
  const auto& [box_lo, box_hi] = partition.box(mpi_run::rank());
  const Vec2 lo = box_lo - Vec2::Constant(halo * (1 + 1e-9)), hi = box_hi + Vec2::Constant(halo * (1 + 1e-9));
  const auto near = [&](const std::array<Vec2, 3>& t) {
    const Vec2 tlo = t[0].cwiseMin(t[1]).cwiseMin(t[2]), thi = t[0].cwiseMax(t[1]).cwiseMax(t[2]);
    return !(thi.x() < lo.x() || thi.y() < lo.y() || tlo.x() > hi.x() || tlo.y() > hi.y());
  };
  const std::array<Vec2, 3> first = triangles.front();
  triangles.erase(std::remove_if(triangles.begin(), triangles.end(), [&](const auto& t) { return !near(t); }),
                  triangles.end());
  if (triangles.empty()) triangles.push_back(first);
}

}  // namespace

void RemeshPipeline::set_domain(const Vec2& wall_lo, const Vec2& wall_hi, const std::vector<Vec2>& pts) {
  domain_lo_ = wall_lo;  // the walls' box (empty without walls), enlarged to every particle
  domain_hi_ = wall_hi;
  for (const auto& q : pts) {
    domain_lo_ = domain_lo_.cwiseMin(q);
    domain_hi_ = domain_hi_.cwiseMax(q);
  }
  const double margin = s_.domain_margin * (domain_hi_ - domain_lo_).maxCoeff();
  domain_lo_ -= Vec2::Constant(margin);
  domain_hi_ += Vec2::Constant(margin);
}

void RemeshPipeline::extend_domain(const std::vector<Vec2>& points) {
  if (domain_lo_.x() <= domain_hi_.x()) {
    const double margin = structure_margin();
    for (const auto& q : points) {
      domain_lo_ = domain_lo_.cwiseMin(q - Vec2::Constant(margin));
      domain_hi_ = domain_hi_.cwiseMax(q + Vec2::Constant(margin));
    }
  }
}

void RemeshPipeline::initial_mesh() {
  if (s_.detection == meshing::DomainDetection::Alpha) {
    remesh_now();
    return;
  }
  meshing::PreviousDomain regions(std::move(region_triangles_), {});
  const Settings keep = s_;
  s_.detection = meshing::DomainDetection::LevelSet;
  s_.level_set_band = 0.0;
  remesh_now(&regions);
  s_ = keep;
  added_outside_ = separated_ = 0;
}

void RemeshPipeline::remesh_step(double t_new, VolumeCorrection& volume, const FluidEnergy& energy,
                                 const std::vector<char>& on_wall_in) {
  std::vector<char> on_wall = on_wall_in;
  // "volume_correction": "particle": the particles' shares of the last mesh, and where each particle is
  // after the remesh (VolumeCorrection::owe_remesh_change).
  const bool owe = volume.type() == VolumeCorrection::Type::particle;
  std::vector<double> before;
  std::vector<Index> present;
  if (owe) {
    before = mesh_.nodal_areas(cloud_.x(), cloud_.n());
    present.resize(before.size());
    std::iota(present.begin(), present.end(), Index{0});
  }
  if (drop_outside_domain(t_new, volume)) {  // the flags follow the renumbering
    if (!on_wall.empty()) {
      std::vector<char> kept(static_cast<size_t>(cloud_.n()), 0);
      for (size_t i = 0; i < on_wall.size() && i < renumber_.size(); ++i)
        if (renumber_[i] >= 0) kept[static_cast<size_t>(renumber_[i])] = on_wall[i];
      on_wall.swap(kept);
    }
    for (Index& k : present) k = renumber_[k];
  }
  // What the remesh changes: area, kinetic and potential energy on the old mesh (the fluid that left the
  // domain box is counted apart, VolumeCorrection's area_left) against the new one.
  const FluidEnergy::Totals before_remesh = energy.totals_over_processes();
  const double area0 = before_remesh.area, ke0 = before_remesh.kinetic, pe0 = before_remesh.potential;
  const std::vector<double> strip0 = outlet_strip_areas();
  t_remesh_ = t_new;
  if (s_.detection == meshing::DomainDetection::Alpha) {
    remesh_now();
    if (size_.adaptive() && follow_size_field_alpha(t_new)) remesh_now();
    const bool removed = remove_close_particles();
    if (removed) remesh_now();
    if (insert_particles()) remesh_now();
  } else {
    const BoundaryChains chain = boundary_chains();
    if (size_.adaptive()) follow_size_field(chain, on_wall, t_new);
    AdvectedDomain advected = advected_domain(chain);  // at the positions before the management
    std::vector<std::uint8_t> meshed;
    std::vector<std::pair<Index, Index>> edges, all_edges;
    manage_particles(chain, meshed, edges, s_.keep_edges_angle > 0 ? &all_edges : nullptr, on_wall);
    for (Index& k : present)
      if (k >= 0) k = survivor_[k];
    // An MPI run with the advected detection: the managed particles' parts (remesh_over_processes), and of the
    // advected elements those that meet this process's part grown by the ghost layer, the only ones that can hold a
    // point its triangulation asks about.
    std::unique_ptr<meshing::SpacePartition> partition;
    if (mpi_run::size() > 1 && s_.detection == meshing::DomainDetection::Advected) {
      partition = std::make_unique<meshing::SpacePartition>(cloud_.positions(), mpi_run::size());
      keep_near_part(advected.triangles, *partition, divided_halo(cloud_.h(), s_.alpha, s_.separation_alpha));
    }
    meshing::PreviousDomain previous(std::move(advected.triangles), std::move(advected.boundary));
    previous.set_topology(std::move(meshed), std::move(edges));
    previous.set_edges(std::move(all_edges));
    try {
      remesh_now(&previous, partition.get());
    } catch (const SolverError&) {
      // The management changed the cloud and the mesh (merged, split, inserted particles) before the
      // triangulation failed; the retry starts from them. What it changed is owed now, as after a remesh
      // that succeeded, or the retry would take the managed mesh's shares as its own `before` and the
      // change would be lost from the bookkeeping (dam_break_obstacle with the advected domain: 2.8 % of
      // the water in four failed remeshes).
      if (owe) volume.owe_remesh_change(before, present);
      throw;
    }
  }
  if (owe) volume.owe_remesh_change(before, present);
  const FluidEnergy::Totals after_remesh = energy.totals_over_processes();
  const double area1 = after_remesh.area;
  remesh_dA_ = area1 - area0;
  // What the remesh changed in an outflow's strip (it fills part of the ragged end the outflow's elements left)
  // comes back from what that outflow took.
  if (strip_) {
    const std::vector<double> strip1 = outlet_strip_areas();
    const auto at = [](const std::vector<double>& a, size_t k) { return k < a.size() ? a[k] : 0.0; };
    for (size_t k = 0; k < std::max(strip0.size(), strip1.size()); ++k) {
      const double back = at(strip1, k) - at(strip0, k);
      if (back == 0.0) continue;
      volume.add_left(-back);
      left_(static_cast<int>(k), 0, -back);
    }
    volume.rebase();
  }
  remesh_dKE_ = after_remesh.kinetic - ke0;
  (remesh_dA_ > 0 ? remesh_area_added_ : remesh_area_removed_) += std::abs(remesh_dA_);
  remesh_ke_total_ += remesh_dKE_;
  remesh_pe_total_ += after_remesh.potential - pe0;
  if (volume.type() == VolumeCorrection::Type::surface) {
    // The faces of inflows and outflows are boundaries of the mesh but not free surface: moved outwards, an
    // inlet's face would be carried out of the channel and an outlet's would push water out. The particles on
    // walls as constraints stay on their lines (set_wall_lines).
    std::vector<char> still;
    if (at_open_face_ || on_wall_line_) {
      still.assign(static_cast<size_t>(cloud_.n()), 0);
      for (Index i = 0; i < cloud_.n(); ++i) {
        const Vec2 p = cloud_.pos(i);
        still[static_cast<size_t>(i)] = (at_open_face_ && at_open_face_(p)) || (on_wall_line_ && on_wall_line_(p));
      }
    }
    volume.restore_area(still);
  }
}

void RemeshPipeline::remesh_now(const meshing::PreviousDomain* previous, const meshing::SpacePartition* partition) {
  const std::vector<ParticleKind>& kind = cloud_.kind();
  const std::vector<Vec2> pts = cloud_.positions();
  meshing::RemeshResult r;
  meshing::RemeshSettings settings;
  settings.alpha = s_.alpha;
  if (previous != nullptr && !previous->empty()) {
    settings.detection = s_.detection;
    settings.previous = previous;
    settings.separation_alpha = s_.separation_alpha;
    settings.level_set_band = s_.level_set_band;
    settings.contact_gap = s_.contact_gap;
    settings.keep_edges_angle = s_.keep_edges_angle;
  }
  // Walls as constraints: the fluid particles on a fixed wall's line (the separation test leaves the water against
  // the wall).
  std::vector<std::uint8_t> on_wall;
  if (on_fixed_wall_line_ && settings.previous != nullptr) {
    on_wall.resize(pts.size());
    for (size_t i = 0; i < pts.size(); ++i) on_wall[i] = kind[i] == ParticleKind::Fluid && on_fixed_wall_line_(pts[i]);
    settings.on_wall = &on_wall;
    settings.along_wall = on_fixed_wall_line_;
  }
  try {
    r = remesh_over_processes(pts, kind, cloud_.h(), settings, &divided_, partition);
  } catch (const std::exception& e) {
    throw SolverError("body '" + c_.name + "': remeshing failed: " + e.what());
  }
  const std::vector<std::array<Index, 3>> boundary_only = std::move(r.boundary_only);
  added_outside_ += r.added_outside;
  kept_edges_ += r.kept_edges;
  separated_ += r.separated_inside;
  if (previous != nullptr && !previous->empty()) {
    // The area of the elements added outside the advected domain (surfaces meeting), less that of those torn
    // off inside it (separation): summary.json, where a splash's area comes from.
    const auto area = [&](const std::array<Index, 3>& t) {
      const Vec2 a = pts[t[0]], b = pts[t[1]], c = pts[t[2]];
      return 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    };
    for (Index e : r.added_elements) area_excess_ += area(r.triangles[static_cast<size_t>(e)]);
    for (const auto& t : r.separated) area_excess_ -= area(t);
  }
  auto& tri = mesh_.tri;
  tri = std::move(r.triangles);
  mesh_.free = std::move(r.free_surface);
  mesh_.connected = std::move(r.connected);
  // Meniscus elements: two wall particles and one free-surface fluid particle. Beside a wall above the
  // water line such an element is air, but it passes the alpha test (its circumradius is h/sqrt(2)); kept,
  // its PSPG gravity term has no hydrostatic gradient to balance it, and the surface particle next to the
  // wall is driven up and down the wall (spurious currents in a tank at rest). Removing them costs a
  // wedge of h^2/2 at a front sliding on a wall, where the front particle stays connected through its
  // other elements.
  // With the advected domain (previous != nullptr) a meniscus element is only ever there because the fluid
  // was: new ones are not added (meshing/remesh.cpp), and existing ones go by the separation test.
  const bool meniscus_filter = previous == nullptr || previous->empty();
  // The element's size: its largest particle's.
  const auto element_h = [&](const std::array<Index, 3>& t) {
    return std::max({cloud_.h(t[0]), cloud_.h(t[1]), cloud_.h(t[2])});
  };
  size_t kept = 0;
  bool removed = false;
  const Vec& xs = cloud_.x();
  const auto above_its_fluid = [&](const std::array<Index, 3>& t) {
    // With graded particles (an adaptive size field) a wall's corner below the surface is often such an element too
    // (on a lattice it never is): there only an element whose centroid lies above (against gravity) its fluid
    // particle is air. The test is kept to graded particles: on uniform ones it let the remeshed standing wave of
    // cases/sloshing_free gain more energy and moved the dam break on a dry floor (decision 0013's addendum).
    if (!size_.adaptive() || c_.gravity.squaredNorm() == 0) return true;
    Vec2 centroid = Vec2::Zero(), fluid = Vec2::Zero();
    for (Index i : t) {
      centroid += xs.segment<2>(2 * i) / 3.0;
      if (kind[i] == ParticleKind::Fluid) fluid = xs.segment<2>(2 * i);
    }
    return (centroid - fluid).dot(c_.gravity) < 0;
  };
  for (size_t e = 0; e < tri.size(); ++e) {
    int walls = 0, free_fluid = 0;
    for (Index i : tri[e]) {
      walls += kind[i] != ParticleKind::Fluid;
      free_fluid += kind[i] == ParticleKind::Fluid && mesh_.free[i];
    }
    if ((meniscus_filter && walls == 2 && free_fluid == 1 && above_its_fluid(tri[e])) ||
        mesh_.element_area(cloud_.x(), static_cast<Index>(e)) <
            s_.flat_fraction * element_h(tri[e]) * element_h(tri[e]) ||
        (ghosts_.particles() > 0 && ghosts_.crosses_structure(tri[e]))) {
      removed = true;
      continue;
    }
    tri[kept++] = tri[e];
  }
  tri.resize(kept);
  if (removed) {
    std::vector<char> walls(cloud_.n(), 0);
    for (Index i = 0; i < cloud_.n(); ++i) walls[i] = kind[i] != ParticleKind::Fluid;
    mark_free_surface(walls);
  }
  find_wet_corners(boundary_only, t_remesh_);
}

void RemeshPipeline::find_wet_corners(const std::vector<std::array<Index, 3>>& faces, double t) {
  wet_corners_.clear();
  if (!wall_depth_ || s_.detection == meshing::DomainDetection::Alpha) return;
  const std::vector<ParticleKind>& kind = cloud_.kind();
  std::vector<std::array<Index, 3>> candidates;
  for (const auto& f : faces) {
    if (kind[f[0]] != ParticleKind::Wall || kind[f[1]] != ParticleKind::Wall || kind[f[2]] != ParticleKind::Wall)
      continue;
    if (!(wall_depth_((cloud_.pos(f[0]) + cloud_.pos(f[1]) + cloud_.pos(f[2])) / 3.0, t) > 0)) candidates.push_back(f);
  }
  if (candidates.empty()) return;
  // The edges between two wall particles of the mesh's elements, then those of the corners taken, until none is
  // added (a corner's fan of several triangles reaches the mesh through its neighbours).
  std::vector<std::pair<Index, Index>> edges;
  const auto edge = [](Index a, Index b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for (const auto& e : mesh_.tri)
    for (int k = 0; k < 3; ++k)
      if (kind[e[k]] == ParticleKind::Wall && kind[e[(k + 1) % 3]] == ParticleKind::Wall)
        edges.push_back(edge(e[k], e[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  std::vector<char> taken(candidates.size(), 0);
  for (bool grew = true; grew;) {
    grew = false;
    std::vector<std::pair<Index, Index>> added;
    for (size_t c = 0; c < candidates.size(); ++c) {
      if (taken[c]) continue;
      const auto& f = candidates[c];
      for (int k = 0; k < 3 && !taken[c]; ++k)
        taken[c] = std::binary_search(edges.begin(), edges.end(), edge(f[k], f[(k + 1) % 3]));
      if (!taken[c]) continue;
      grew = true;
      wet_corners_.push_back(f);
      for (int k = 0; k < 3; ++k) added.push_back(edge(f[k], f[(k + 1) % 3]));
    }
    edges.insert(edges.end(), added.begin(), added.end());
    std::sort(edges.begin(), edges.end());
  }
}

void RemeshPipeline::mark_free_surface(const std::vector<char>& on_wall,
                                       const std::function<bool(const Vec2&)>& along_wall) {
  const Index np = cloud_.n();
  mesh_.connected.assign(np, 0);
  for (const auto& t : mesh_.tri)
    for (Index i : t) mesh_.connected[i] = 1;
  mesh_.free.assign(np, 0);
  const Vec& x = cloud_.x();
  for (const auto& [e, k] : mesh_.boundary_edges()) {
    const Index a = mesh_.tri[e][k], b = mesh_.tri[e][(k + 1) % 3];
    if (on_wall[a] && on_wall[b] && (!along_wall || along_wall(0.5 * (x.segment<2>(2 * a) + x.segment<2>(2 * b)))))
      continue;
    for (Index i : {a, b})
      if (cloud_.kind(i) == ParticleKind::Fluid) mesh_.free[i] = 1;
  }
}

bool RemeshPipeline::remove_close_particles() {
  // Particles pressed together (impacts, the wall) make near-flat elements that invert within a step.
  // Of a fluid-fluid pair closer than close_fraction * h one particle goes (meshing picks it); a fluid
  // particle closer than that to a wall particle goes. The fluid area is measured on the elements, so
  // the mass this removes shows in the area drift.
  if (s_.close_fraction <= 0) return false;
  const std::vector<ParticleKind>& kind = cloud_.kind();
  const std::vector<Vec2> pts = cloud_.positions();
  std::vector<char> drop(cloud_.n(), 0);
  for (Index i : meshing::close_fluid_particles(pts, kind, cloud_.h(), mesh_.tri, s_.close_fraction)) drop[i] = 1;
  for (const auto& t : mesh_.tri)
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k], b = t[(k + 1) % 3];
      const bool fa = kind[a] == ParticleKind::Fluid, fb = kind[b] == ParticleKind::Fluid;
      if (fa == fb) continue;
      const Index f = fa ? a : b;
      if ((pts[a] - pts[b]).norm() < s_.close_fraction * cloud_.h(f)) drop[f] = 1;
    }
  return drop_particles(drop);
}

bool RemeshPipeline::insert_particles() {
  // Where the flow stretches the particle distribution, elements grow until the alpha test deletes them
  // and the fluid tears; a particle at the centroid of every element larger than insert_factor * h^2
  // (with the element's mean velocity, acceleration and pressure) keeps the spacing near h.
  if (s_.insert_factor <= 0) return false;
  const std::vector<Vec2> pts = cloud_.positions();
  const auto big = meshing::oversized_elements(pts, cloud_.h(), mesh_.tri, s_.insert_factor);
  if (big.empty()) return false;
  const Vec &xs = cloud_.x(), &vs = cloud_.v(), &as = cloud_.a(), &ps = cloud_.p();
  std::vector<ParticleCloud::Particle> added;
  added.reserve(big.size());
  for (Index e : big) {
    const auto& t = mesh_.tri[e];
    Vec2 x = Vec2::Zero(), v = Vec2::Zero(), a = Vec2::Zero();
    double p = 0, hh = 0;
    for (Index i : t) {
      x += xs.segment<2>(2 * i) / 3.0;
      v += vs.segment<2>(2 * i) / 3.0;
      a += as.segment<2>(2 * i) / 3.0;
      p += ps[i] / 3.0;
      hh += cloud_.h(i) / 3.0;
    }
    added.push_back(fluid_particle(x, v, a, p, hh));
  }
  cloud_.append(added);
  return true;
}

bool RemeshPipeline::drop_outside_domain(double t_new, VolumeCorrection& volume) {
  // Fluid particles that left the domain box (walls and initial fluid, enlarged by domain_margin times the
  // larger side) are gone: a jet that falls off the end of a floor would otherwise fly forever. The box is
  // open on the side gravity points away from: a splash thrown above the walls falls back.
  const bool box = domain_lo_.x() <= domain_hi_.x();
  if (!box && !taker_) return false;
  // The box follows a structure that moves (its ghost particles, with extend_domain's margin): the water a
  // plate pushed 23 mm away holds past the first box is not gone (cases/flexible_tank lost 0.24 % of its
  // area there). So it does moving walls: a tank carried 0.5 m sideways lost nearly all its water.
  Vec2 box_lo = domain_lo_, box_hi = domain_hi_;
  const double margin = structure_margin();
  for (Index i = 0; i < cloud_.n(); ++i)
    if (cloud_.kind(i) == ParticleKind::Ghost) {
      box_lo = box_lo.cwiseMin(cloud_.pos(i) - Vec2::Constant(margin));
      box_hi = box_hi.cwiseMax(cloud_.pos(i) + Vec2::Constant(margin));
    }
  if (walls_lo_.x() <= walls_hi_.x()) {
    box_lo = box_lo.cwiseMin(walls_lo_ - Vec2::Constant(margin));
    box_hi = box_hi.cwiseMax(walls_hi_ + Vec2::Constant(margin));
  }
  const Vec2 g = c_.gravity;
  const Vec2 lo(g.x() > 0 ? -std::numeric_limits<double>::infinity() : box_lo.x(),
                g.y() > 0 ? -std::numeric_limits<double>::infinity() : box_lo.y());
  const Vec2 hi(g.x() < 0 ? std::numeric_limits<double>::infinity() : box_hi.x(),
                g.y() < 0 ? std::numeric_limits<double>::infinity() : box_hi.y());
  std::vector<char> drop(cloud_.n(), 0);
  std::vector<int> taken_by(taker_ ? static_cast<size_t>(cloud_.n()) : 0, -1);  // the outflow that took it
  bool any = false;
  Index fluid_left = 0;
  for (Index i = 0; i < cloud_.n(); ++i) {
    if (cloud_.kind(i) != ParticleKind::Fluid) continue;
    const Vec2 q = cloud_.pos(i);
    const int outflow = taker_ ? taker_(q) : -1;
    if (outflow >= 0) taken_by[static_cast<size_t>(i)] = outflow;
    if (outflow >= 0 || (box && (q.x() < lo.x() || q.y() < lo.y() || q.x() > hi.x() || q.y() > hi.y()))) {
      drop[i] = 1;
      any = true;
    } else {
      ++fluid_left;
    }
  }
  if (!any) return false;
  if (fluid_left == 0)
    throw SolverError("body '" + c_.name +
                      "': all fluid particles left the domain box by t = " + std::to_string(t_new));
  // The fluid that left is gone: its share of the last mesh (A_e / 3 per dropped particle of each element)
  // leaves the reference area too, so that the volume correction does not make it up elsewhere.
  // An element with a particle an outflow takes leaves whole with it: the mesh then ends at the particles behind
  // it (a particle's third of its elements would count half the strip the outlet loses at each removal).
  for (Index e = 0; e < mesh_.num_elements(); ++e) {
    int outflow = -1;
    for (Index i : mesh_.tri[e])
      if (outflow < 0 && !taken_by.empty()) outflow = taken_by[static_cast<size_t>(i)];
    if (outflow >= 0) {
      const double a = mesh_.element_area(cloud_.x(), e);
      volume.add_left(a);
      left_(outflow, 0, a);
      continue;
    }
    for (Index i : mesh_.tri[e])
      if (drop[i]) volume.add_left(mesh_.element_area(cloud_.x(), e) / 3.0);
  }
  for (size_t i = 0; i < taken_by.size(); ++i)
    if (taken_by[i] >= 0) left_(taken_by[i], 1, 0.0);
  // With "volume_correction": "particle", the area each owed (a drop in flight: all of its own) leaves too.
  if (volume.type() == VolumeCorrection::Type::particle)
    for (Index i = 0; i < cloud_.n(); ++i)
      if (drop[i]) volume.add_left(cloud_.owed()[i]);
  volume.rebase();
  return drop_particles(drop);
}

std::vector<double> RemeshPipeline::outlet_strip_areas() const {
  std::vector<double> area;
  if (!strip_) return area;
  for (Index e = 0; e < mesh_.num_elements(); ++e) {
    const auto& t = mesh_.tri[e];
    const int k = strip_((cloud_.pos(t[0]) + cloud_.pos(t[1]) + cloud_.pos(t[2])) / 3.0);
    if (k < 0) continue;
    if (area.size() <= static_cast<size_t>(k)) area.resize(static_cast<size_t>(k) + 1, 0.0);
    area[static_cast<size_t>(k)] += mesh_.element_area(cloud_.x(), e);
  }
  return area;
}

bool RemeshPipeline::drop_particles(const std::vector<char>& drop) {
  const Index np = cloud_.n();
  renumber_.assign(np, -1);
  Index kept = 0;
  for (Index i = 0; i < np; ++i)
    if (!drop[i]) renumber_[i] = kept++;
  if (!cloud_.compact(drop)) return false;
  auto& tri = mesh_.tri;
  size_t kept_elements = 0;
  for (const auto& t : tri) {
    if (renumber_[t[0]] < 0 || renumber_[t[1]] < 0 || renumber_[t[2]] < 0) continue;
    tri[kept_elements++] = {renumber_[t[0]], renumber_[t[1]], renumber_[t[2]]};
  }
  tri.resize(kept_elements);
  return true;
}

void RemeshPipeline::append_particle(const Vec2& x, const Vec2& v, const Vec2& a, double p, double h) {
  cloud_.append({fluid_particle(x, v, a, p, h)});
}

Json RemeshPipeline::summary() const {
  Json j = {{"area_added", remesh_area_added_},
            {"area_removed", remesh_area_removed_},
            {"kinetic_energy_change", remesh_ke_total_},
            {"potential_energy_change", remesh_pe_total_},
            {"particles_merged", merged_},
            {"pairs_merged_meeting", merged_meeting_},
            {"edges_split", split_},
            {"particles_inserted", inserted_},
            {"particles_removed_at_walls", wall_removed_},
            {"elements_added_outside", added_outside_},
            {"edges_kept", kept_edges_},
            {"elements_separated", separated_},
            {"area_of_added_minus_separated_elements", area_excess_}};
  if (size_.adaptive()) j["particles_coarsened"] = coarsened_;
  if (divided_.remeshes > 0) j["divided"] = divided_.summary(mpi_run::size());
  return j;
}

}  // namespace lagfsi::fluid
