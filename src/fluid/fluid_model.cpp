// PFEM fluid: particles carrying positions, velocities, accelerations and pressure; the mesh is rebuilt
// from the particles at every step (Delaunay + alpha shape, meshing/remesh.hpp) or kept fixed; the unknowns
// of a step are the new positions and pressures, solved by Newton on the stabilized (PSPG) position-pressure
// system of Avancini (2018) ch. 6, in the self-consistent form of the digest (p positive in compression):
//
//   R^m_a = sum_e [ M_ab a_b + K_ab v_b - G_ab p_b - f_a ]                    (momentum, 2 per particle)
//   R^c_a = sum_e [ (A/3) div v + tau A grad N_a . (a_avg - g) + (tau/rho) A grad N_a . grad p
//                   + (A/3) c_vol ]                                        (continuity, 1 per particle)
//
// with P1 shape functions on the current (last iterate) configuration, Newmark (or generalized-alpha)
// kinematics a(x), v(x) from the shared time integrators, and the tangent at frozen geometry
// (d/dx of grad N and A neglected; Ryzhakov et al. 2010). c_vol is the optional global volume-correction
// source ("volume_correction": "source"); the default correction ("surface") is geometric, see restore_area.
#include "fluid_model.hpp"

#include <sstream>
#include <unordered_map>

namespace lagfsi {
namespace fluid_detail {
namespace {
/// Points hashed on a square grid of cell size `cell`: "is there a point within r <= cell of p" in O(1), for
/// building the particle set (shared wall corners, fluid particles next to walls or on a region's border),
/// which compared every pair before (hours at a millionth of the default spacing).
class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell) {}
  void add(const Vec2& p, Index id) { cells_[key(std::floor(p.x() / cell_), std::floor(p.y() / cell_))].push_back(id); }
  /// The last added point within r of p among `pts`, or -1.
  Index find(const Vec2& p, double r, const std::vector<Vec2>& pts) const {
    const double cx = std::floor(p.x() / cell_), cy = std::floor(p.y() / cell_);
    Index found = -1;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (Index j : it->second)
          if ((pts[static_cast<size_t>(j)] - p).norm() < r) found = std::max(found, j);
      }
    return found;
  }

 private:
  struct Key {
    double x, y;
    bool operator==(const Key& o) const { return x == o.x && y == o.y; }
  };
  struct Hash {
    size_t operator()(const Key& k) const { return std::hash<double>()(k.x) * 1000003u ^ std::hash<double>()(k.y); }
  };
  static Key key(double x, double y) { return {x, y}; }
  double cell_;
  std::unordered_map<Key, std::vector<Index>, Hash> cells_;
};


class FluidProbe final : public Probe {
 public:
  FluidProbe(const FluidModel& m, std::string name, std::string type, Params p);
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;

 private:
  const FluidModel& m_;
  std::string name_, type_;
  Vec2 a_ = Vec2::Zero(), b_ = Vec2::Zero();
  double band_ = 0, coord_ = 0;
  bool mesh_method_ = true;
};

}  // namespace


// ------------------------------------------------------------------------------------------ building

FluidModel::FluidModel(Params b, const CaseContext& ctx) : ctx_(ctx) {
  b.validate({{"name", nullptr},
              {"type", "fluid"},
              {"density", nullptr},
              {"viscosity", nullptr},
              {"spacing", nullptr},
              {"alpha", 1.2},
              {"domain_detection", "alpha"},
              {"separation_alpha", 2.5},
              {"level_set_band", 0.25},
              {"domain_margin", 0.1},
              {"remesh", true},
              {"regions", nullptr},
              {"particles", "structured"},
              {"walls", Json::array()},
              {"initial_velocity", Json::array({0.0, 0.0})},
              {"initial_pressure", Json{{"type", "zero"}}},
              {"initial_state", Json{{"type", "given"}}},
              {"scheme", Json::object()}});
  name_ = b.identifier("name");
  if (ctx.analysis.type != "dynamic") b.fail("type", "a fluid needs a dynamic analysis");
  rho_ = b.positive("density");
  mu_ = b.non_negative("viscosity");
  h_ = b.positive("spacing");
  alpha_ = b.positive("alpha");
  if (alpha_ < 1.0 || alpha_ > 5.0) b.fail("alpha", "must lie in [1, 5] (the literature uses 1.0-1.5)");
  remesh_ = b.boolean("remesh");
  const std::string detection = b.choice("domain_detection", {"alpha", "advected", "level_set"});
  detection_ = detection == "alpha"      ? meshing::DomainDetection::Alpha
               : detection == "advected" ? meshing::DomainDetection::Advected
                                         : meshing::DomainDetection::LevelSet;
  separation_alpha_ = b.positive("separation_alpha");
  if (separation_alpha_ < alpha_) b.fail("separation_alpha", "must be at least alpha (" + std::to_string(alpha_) + ")");
  level_set_band_ = b.non_negative("level_set_band");
  domain_margin_ = b.non_negative("domain_margin");

  Params s = b.at("scheme");
  if (!s.json().is_object()) s.fail("must be an object");
  scheme_ = s.has("type") ? s.choice("type", {"monolithic_pspg", "fractional_step"}) : "monolithic_pspg";
  // Keys common to both schemes (particles, mass conservation), then each scheme's own.
  Json keys = {{"type", scheme_},
               // The alpha shape changes the area at every remesh and needs the surface correction; the
               // advected and level-set detections keep it where the topology does not change.
               {"volume_correction", detection_ == meshing::DomainDetection::Alpha ? "surface" : "none"},
               {"split_edge_factor", 1.6},
               {"volume_relaxation_time", 0.1},
               {"remove_close_fraction", 0.3},
               {"insert_area_factor", 1.0},
               {"bulk_modulus", 2.2e9},
               {"flat_element_fraction", 0.01}};
  if (scheme_ == "monolithic_pspg") {
    keys.update(Json{{"tau", Json{{"type", "automatic"}}},
                     {"mass", "lumped"},
                     {"free_surface_pressure", "dirichlet"},
                     {"tolerance", 1e-4},
                     {"refactorize_every", 0},
                     {"linear_solver", "klu"}});
  } else {
    keys.update(Json{{"viscous_step", "automatic"}, {"linear_solver", "cholmod"}, {"inverted_elements", "retry"}});
  }
  s.validate(keys);
  if (scheme_ == "monolithic_pspg") {
    Params tau = s.at("tau");
    if (!tau.json().is_object() || !tau.has("type")) tau.fail("type", "required key is missing");
    tau_type_ = tau.choice("type", {"automatic", "velocity_scale"});
    if (tau_type_ == "automatic") {
      tau.validate({{"type", "automatic"}});
    } else {
      tau.validate({{"type", "velocity_scale"}, {"U", nullptr}});
      tau_U_ = tau.positive("U");
    }
    lumped_ = s.choice("mass", {"lumped", "consistent"}) == "lumped";
    p_free_dirichlet_ = s.choice("free_surface_pressure", {"dirichlet", "natural"}) == "dirichlet";
    tol_ = s.positive("tolerance");
    refactor_every_ = s.integer("refactorize_every", 0);
    solver_type_ = s.choice("linear_solver", {"umfpack", "klu", "eigen_lu"});
  } else {
    // Fractional step: lumped mass, Dirichlet free-surface pressure, symmetric positive definite solves.
    viscous_step_ = s.choice("viscous_step", {"automatic", "explicit", "implicit"});
    solver_type_ = s.choice("linear_solver", {"cholmod", "cholmod_supernodal", "eigen_ldlt"});
    retry_inverted_ = s.choice("inverted_elements", {"retry", "remesh"}) == "retry";
  }
  volume_correction_ = s.choice("volume_correction", {"surface", "source", "none"});
  relax_time_ = s.positive("volume_relaxation_time");
  close_fraction_ = s.non_negative("remove_close_fraction");
  bulk_ = s.non_negative("bulk_modulus");
  insert_factor_ = s.non_negative("insert_area_factor");
  flat_fraction_ = s.non_negative("flat_element_fraction");
  split_factor_ = s.non_negative("split_edge_factor");
  if (split_factor_ > 0 && split_factor_ < 1.0) s.fail("split_edge_factor", "must be 0 (off) or at least 1");
  if (close_fraction_ >= 0.9) s.fail("remove_close_fraction", "must be below 0.9");

  Params it(ctx.analysis.integrator, ctx.case_file.string(), "/analysis/integrator");
  const std::string itype = it.string("type");
  integrator_ = itype == "generalized_alpha" ? make_generalized_alpha(it.number("rho_inf"))
                                             : make_newmark(it.number("beta"), it.number("gamma"));
  solver_ = make_linear_solver(solver_type_);
  if (scheme_ == "fractional_step") viscous_solver_ = make_linear_solver(solver_type_);
  build_particles(b);
}

void FluidModel::build_particles(Params b) {
  // Walls first (their particles take precedence over fluid particles at the same place).
  Params walls = b.at("walls");
  for (size_t i = 0; i < walls.size(); ++i) {
    Params w = walls.at(i);
    w.validate({{"name", "wall" + std::to_string(i)},
                {"points", nullptr},
                {"slip", false},
                {"motion", Json::object()}});
    Wall wall;
    wall.name = w.string("name");
    wall.polyline = w.points("points");
    if (wall.polyline.size() < 2) w.fail("points", "a wall needs at least two points");
    for (size_t k = 0; k + 1 < wall.polyline.size(); ++k)
      if (!((wall.polyline[k + 1] - wall.polyline[k]).norm() > 1e-6 * h_))
        w.fail("points", "segment " + std::to_string(k) + " has zero length (points " + std::to_string(k) + " and " +
                             std::to_string(k + 1) + " coincide)");
    wall.slip = w.boolean("slip");
    Params mo = w.at("motion");
    if (!mo.json().empty()) {
      if (!mo.has("type")) mo.fail("type", "required key is missing");
      const std::string mt = mo.choice("type", {"prescribed_displacement", "prescribed_velocity"});
      mo.validate({{"type", mt}, {"value", nullptr}, {"function", nullptr}});
      wall.value = mo.vec2("value");
      wall.fn = make_time_function(mo.at("function"), ctx_.base_dir);
      wall.velocity = mt == "prescribed_velocity";
    }
    walls_.push_back(std::move(wall));
  }

  std::vector<Vec2> pts;
  auto add = [&](const Vec2& p, ParticleKind k) {
    pts.push_back(p);
    kind_.push_back(k);
  };
  PointGrid wall_grid(0.5 * h_), fluid_grid(0.5 * h_);   // the particles so far, for the proximity tests
  if (remesh_) {
    double wall_particles = 0;
    for (const auto& w : walls_)
      for (size_t s = 0; s + 1 < w.polyline.size(); ++s) wall_particles += (w.polyline[s + 1] - w.polyline[s]).norm() / h_;
    if (!(wall_particles <= 1e6)) walls.fail("more than a million wall particles at this spacing");
    for (auto& w : walls_) {
      for (size_t s = 0; s + 1 < w.polyline.size(); ++s) {
        const Vec2 a = w.polyline[s], c = w.polyline[s + 1];
        const int n = std::max(1, static_cast<int>(std::ceil((c - a).norm() / h_ * (1 - 1e-12))));
        for (int k = (s == 0 ? 0 : 1); k <= n; ++k) {
          const Vec2 p = a + (c - a) * (double(k) / n);
          // Shared corner with an earlier wall: reuse its particle.
          const Index found = wall_grid.find(p, 1e-9 * h_, pts);
          if (found < 0) {
            w.particles.push_back(static_cast<Index>(pts.size()));
            wall_grid.add(p, static_cast<Index>(pts.size()));
            add(p, ParticleKind::Wall);
            slip_particle_.push_back(w.slip);
          } else {
            w.particles.push_back(found);
            slip_particle_[found] = slip_particle_[found] || w.slip;
          }
        }
      }
    }
  }
  const Index n_wall = static_cast<Index>(pts.size());

  // Fluid regions: particles on a square lattice of spacing h (structured) or the nodes of a Delaunay
  // mesh of size h (unstructured); in PFEM mode, fluid particles closer than h/2 to a wall particle are
  // dropped (the wall particle stands for them).
  Params regions = b.at("regions");
  if (regions.size() == 0) regions.fail("at least one fluid region is needed");
  const std::string layout = b.choice("particles", {"structured", "unstructured"});
  std::vector<Index> fixed_conn;  // fixed-connectivity mode: the initial mesh
  // The walls' bounding box (also the start of the domain box below): a region reaching beyond it by more
  // than the walls' own extent (on an axis where they have one) is a typing error (a size 1000 times too
  // large), which would otherwise be meshed into millions of particles before anything else is checked.
  Vec2 wall_lo = Vec2::Constant(std::numeric_limits<double>::infinity()), wall_hi = -wall_lo;
  for (const auto& w : walls_)
    for (const auto& q : w.polyline) {
      wall_lo = wall_lo.cwiseMin(q);
      wall_hi = wall_hi.cwiseMax(q);
    }
  for (size_t r = 0; r < regions.size(); ++r) {
    Params g = regions.at(r);
    if (!walls_.empty() && g.json().is_object() && g.has("type")) {
      std::vector<Vec2> corners;
      const std::string rt = g.string("type");
      if (rt == "rectangle" && g.has("size")) {
        const Vec2 o = g.has("origin") ? g.vec2("origin") : Vec2::Zero();
        corners = {o, o + g.vec2("size")};
      } else if ((rt == "polygon" || rt == "circle_cut") && g.has("points")) {
        corners = g.points("points");
      }
      for (size_t c = 0; c < corners.size(); ++c)
        for (int axis = 0; axis < 2; ++axis) {
          const Vec2& q = corners[c];
          const double extent = wall_hi[axis] - wall_lo[axis];
          if (extent > 0 && (q[axis] < wall_lo[axis] - extent || q[axis] > wall_hi[axis] + extent)) {
            std::ostringstream os;
            const char* xy = axis ? "y" : "x";
            os << "reaches " << xy << " = " << q[axis] << ", far beyond the walls (" << xy << " from "
               << wall_lo[axis] << " to " << wall_hi[axis] << ")";
            g.fail(rt == "rectangle" ? std::string(c == 0 ? "origin" : "size") : "points/" + std::to_string(c),
                   os.str());
          }
        }
    }
    TriMesh mesh;
    Json mesh_params = {{"size", h_}, {"order", 1}, {"type", "unstructured"}};
    if (layout == "structured") {
      if (!g.has("type") || g.string("type") != "rectangle")
        g.fail("type", "structured particles need rectangle regions (use \"particles\": \"unstructured\")");
      g.validate({{"type", "rectangle"}, {"origin", Json::array({0.0, 0.0})}, {"size", nullptr}});
      const Vec2 sz = g.vec2("size");
      if (!(sz.x() >= 0.5 * h_ && sz.y() >= 0.5 * h_))
        g.fail("size", "each side must be at least half the particle spacing (" + std::to_string(h_) + ")");
      if (!(sz.x() / h_ * (sz.y() / h_) <= 5e6))
        g.fail("size", "more than 5 million particles at this spacing");
      mesh_params = {{"size", h_},
                     {"order", 1},
                     {"type", "structured"},
                     {"divisions",
                      {std::max(1, (int)std::lround(sz.x() / h_)), std::max(1, (int)std::lround(sz.y() / h_))}},
                     {"pattern", "crossed"}};
    }
    mesh = build_mesh(g, Params(mesh_params, b.file(), g.path() + "/(mesh)"));
    for (size_t e = 0; e + 2 < mesh.conn.size(); e += 3)
      region_triangles_.push_back({mesh.nodes[mesh.conn[e]], mesh.nodes[mesh.conn[e + 1]], mesh.nodes[mesh.conn[e + 2]]});
    std::vector<Index> new_particles;   // this region's, added to the grid after the region
    const Index base = static_cast<Index>(pts.size());
    std::vector<Index> map(mesh.nodes.size(), -1);
    for (size_t k = 0; k < mesh.nodes.size(); ++k) {
      const Vec2& q = mesh.nodes[k];
      // Within h/2 of a wall particle, or on the shared boundary with an earlier region.
      const bool near_wall = wall_grid.find(q, 0.5 * h_, pts) >= 0;
      const bool duplicate = r > 0 && fluid_grid.find(q, 1e-9 * h_, pts) >= 0;
      if (near_wall || duplicate) continue;
      map[k] = static_cast<Index>(pts.size());
      new_particles.push_back(map[k]);
      add(q, ParticleKind::Fluid);
    }
    for (Index j : new_particles) fluid_grid.add(pts[static_cast<size_t>(j)], j);
    if (!remesh_) {
      if (regions.size() > 1) regions.fail("fixed connectivity supports one fluid region");
      fixed_conn = mesh.conn;
      for (auto& c : fixed_conn) c = map[c];
    }
    (void)base;
  }
  if (pts.size() == static_cast<size_t>(n_wall)) regions.fail("the regions contain no fluid particle");

  const Index np = static_cast<Index>(pts.size());
  if (remesh_) {
    domain_lo_ = wall_lo;   // the walls' box (empty without walls), enlarged to every particle
    domain_hi_ = wall_hi;
    for (const auto& q : pts) {
      domain_lo_ = domain_lo_.cwiseMin(q);
      domain_hi_ = domain_hi_.cwiseMax(q);
    }
    const double margin = domain_margin_ * (domain_hi_ - domain_lo_).maxCoeff();
    domain_lo_ -= Vec2::Constant(margin);
    domain_hi_ += Vec2::Constant(margin);
  }
  state_.x.resize(2 * np);
  for (Index i = 0; i < np; ++i) state_.x.segment<2>(2 * i) = pts[i];
  X0_ = state_.x;
  // The fluid side of each wall segment: the side of the initial fluid particles that face it (whose
  // projection falls on it; 0 when there are some on both sides, as beside a baffle, or none).
  for (auto& w : walls_) {
    w.fluid_side.assign(w.polyline.size() > 1 ? w.polyline.size() - 1 : 0, 0);
    for (size_t k = 0; k + 1 < w.polyline.size(); ++k) {
      const Vec2 a = w.polyline[k], e = w.polyline[k + 1] - a;
      const Vec2 nrm = Vec2(-e.y(), e.x()).normalized();
      int pos = 0, neg = 0;
      for (Index i = 0; i < np; ++i) {
        if (kind_[i] != ParticleKind::Fluid) continue;
        const double u = (pts[i] - a).dot(e) / e.squaredNorm(), dist = (pts[i] - a).dot(nrm);
        if (u < 0 || u > 1) continue;
        (dist > 0 ? pos : neg) += 1;
      }
      w.fluid_side[k] = pos > 0 && neg == 0 ? 1 : neg > 0 && pos == 0 ? -1 : 0;
    }
  }
  state_.v = Vec::Zero(2 * np);
  const Vec2 v0 = b.vec2("initial_velocity");
  for (Index i = 0; i < np; ++i)
    if (kind_[i] == ParticleKind::Fluid) state_.v.segment<2>(2 * i) = v0;
  state_.a = Vec::Zero(2 * np);
  hvec_.assign(np, h_);
  p_ = Vec::Zero(np);

  Params ip = b.at("initial_pressure");
  if (!ip.has("type")) ip.fail("type", "required key is missing");
  const std::string ipt = ip.choice("type", {"zero", "hydrostatic"});
  if (ipt == "hydrostatic") {
    ip.validate({{"type", "hydrostatic"}, {"level", nullptr}});
    const double level = ip.number("level");
    const double g = ctx_.gravity.norm();
    for (Index i = 0; i < np; ++i) p_[i] = std::max(0.0, rho_ * g * (level - pts[i].y()));
  } else {
    ip.validate({{"type", "zero"}});
  }

  // Analytic initial states (they override initial_velocity and initial_pressure).
  Params is = b.at("initial_state");
  if (!is.has("type")) is.fail("type", "required key is missing");
  const std::string ist = is.choice("type", {"given", "solitary_wave", "taylor_green"});
  if (ist == "taylor_green") {
    // Divergence-free cellular flow of amplitude U on a square [x0, x0 + L]^2 (a test of energy stability:
    // without gravity the kinetic energy of a free blob can only decrease):
    // u = U sin(pi X) cos(pi Y), v = -U cos(pi X) sin(pi Y), X = (x - x0) / L, Y = (y - y0) / L.
    is.validate({{"type", "taylor_green"}, {"amplitude", nullptr}, {"origin", Json::array({0.0, 0.0})},
                 {"length", nullptr}});
    const double U = is.number("amplitude"), Lc = is.positive("length");
    const Vec2 o = is.vec2("origin");
    for (Index i = 0; i < np; ++i) {
      if (kind_[i] != ParticleKind::Fluid) continue;
      const double X = std::numbers::pi * (pts[i].x() - o.x()) / Lc, Y = std::numbers::pi * (pts[i].y() - o.y()) / Lc;
      state_.v[2 * i] = U * std::sin(X) * std::cos(Y);
      state_.v[2 * i + 1] = -U * std::cos(X) * std::sin(Y);
    }
  } else if (ist == "solitary_wave") {
    // Laitone (1960) first-order solitary wave of height H on depth d, crest at x0, moving towards +x:
    // eta = d + H sech^2(k (x - x0)), k = sqrt(3H / (4 d^3)),
    // u = sqrt(g d) (H/d) sech^2, v = sqrt(3 g d) (H/d)^(3/2) (y/d) sech^2 tanh, p = rho g (eta - y).
    is.validate({{"type", "solitary_wave"}, {"depth", nullptr}, {"height", nullptr}, {"crest", nullptr}});
    const double d = is.positive("depth"), H = is.positive("height"), x0 = is.number("crest");
    const double g = ctx_.gravity.norm();
    if (!(g > 0)) is.fail("type", "a solitary wave needs gravity");
    const double k = std::sqrt(3 * H / (4 * d * d * d));
    for (Index i = 0; i < np; ++i) {
      if (kind_[i] != ParticleKind::Fluid) continue;
      const double xi = k * (pts[i].x() - x0), y = pts[i].y();
      const double sech2 = 1.0 / (std::cosh(xi) * std::cosh(xi));
      state_.v[2 * i] = std::sqrt(g * d) * (H / d) * sech2;
      state_.v[2 * i + 1] = std::sqrt(3 * g * d) * std::pow(H / d, 1.5) * (y / d) * sech2 * std::tanh(xi);
      p_[i] = std::max(0.0, rho_ * g * (d + H * sech2 - y));
    }
  } else {
    is.validate({{"type", "given"}});
  }

  if (!remesh_) {
    // Fixed connectivity: the initial mesh for the whole run; walls constrain the fluid nodes on them.
    tri_.clear();
    for (size_t e = 0; e + 2 < fixed_conn.size(); e += 3) tri_.push_back({fixed_conn[e], fixed_conn[e + 1], fixed_conn[e + 2]});
    for (size_t wi = 0; wi < walls_.size(); ++wi) {
      const Wall& w = walls_[wi];
      for (size_t s = 0; s + 1 < w.polyline.size(); ++s) {
        const Vec2 a = w.polyline[s], d = w.polyline[s + 1] - a;
        const bool horizontal = std::abs(d.y()) < 1e-12 * d.norm(), vertical = std::abs(d.x()) < 1e-12 * d.norm();
        if (w.slip && !horizontal && !vertical)
          b.fail("walls", "slip walls must be horizontal or vertical segments in this version");
        for (Index i = 0; i < np; ++i) {
          const double t = std::clamp((pts[i] - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
          if ((pts[i] - (a + t * d)).norm() > 1e-6 * h_) continue;
          if (!w.slip || horizontal) slip_.push_back({i, 1});
          if (!w.slip || vertical) slip_.push_back({i, 0});
        }
      }
    }
  }
}

// ------------------------------------------------------------------------------------------ helpers

double FluidModel::element_area(const Vec& x, Index e) const {
  const auto& t = tri_[e];
  const Vec2 a = x.segment<2>(2 * t[0]), b = x.segment<2>(2 * t[1]), c = x.segment<2>(2 * t[2]);
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

PspgElementInput FluidModel::element_input(Index e, const Vec& x, const Vec& v, const Vec& a, double c_m,
                                           double c_c) const {
  PspgElementInput in;
  const auto& t = tri_[e];
  for (int k = 0; k < 3; ++k) {
    in.x[k] = x.segment<2>(2 * t[k]);
    in.v[k] = v.segment<2>(2 * t[k]);
    in.a[k] = a.segment<2>(2 * t[k]);
    in.p[k] = p_[t[k]];
    in.p_old[k] = p_old_.size() == p_.size() ? p_old_[t[k]] : p_[t[k]];
  }
  in.rho = rho_;
  in.mu = inviscid_element(e) ? 0.0 : mu_;
  in.dt = dt_ > 0 ? dt_ : ctx_.analysis.dt;
  in.tau_U = tau_type_ == "automatic" ? 0.0 : tau_U_;
  in.bulk = bulk_;
  in.c_vol = c_vol_;
  in.g = ctx_.gravity;
  in.lumped = lumped_;
  in.c_m = c_m;
  in.c_c = c_c;
  return in;
}

double FluidModel::kinetic_energy() const {
  double e = 0;
  for (Index k = 0; k < static_cast<Index>(tri_.size()); ++k) {
    const double m = rho_ * element_area(state_.x, k) / 3.0;
    for (Index i : tri_[k]) e += 0.5 * m * state_.v.segment<2>(2 * i).squaredNorm();
  }
  return e;
}

double FluidModel::potential_energy() const {
  double e = 0;
  for (Index k = 0; k < static_cast<Index>(tri_.size()); ++k) {
    Vec2 c = Vec2::Zero();
    for (Index i : tri_[k]) c += state_.x.segment<2>(2 * i);
    e -= rho_ * element_area(state_.x, k) * ctx_.gravity.dot(c / 3.0);
  }
  return e;
}

void FluidModel::remesh_now(const meshing::PreviousDomain* previous) {
  const Index np = n();
  std::vector<Vec2> pts(np);
  for (Index i = 0; i < np; ++i) pts[i] = state_.x.segment<2>(2 * i);
  meshing::RemeshResult r;
  meshing::RemeshSettings settings;
  settings.alpha = alpha_;
  if (previous != nullptr && !previous->empty()) {
    settings.detection = detection_;
    settings.previous = previous;
    settings.separation_alpha = separation_alpha_;
    settings.level_set_band = level_set_band_;
  }
  try {
    r = meshing::remesh(pts, kind_, hvec_, settings);
  } catch (const std::exception& e) {
    throw SolverError("body '" + name_ + "': remeshing failed: " + e.what());
  }
  added_outside_ += r.added_outside;
  separated_ += r.separated_inside;
  tri_ = std::move(r.triangles);
  free_ = std::move(r.free_surface);
  connected_ = std::move(r.connected);
  // Meniscus elements: two wall particles and one free-surface fluid particle. Beside a wall above the
  // water line such an element is air, but it passes the alpha test (its circumradius is h/sqrt(2)); kept,
  // its PSPG gravity term has no hydrostatic gradient to balance it, and the surface particle next to the
  // wall is driven up and down the wall (spurious currents in a tank at rest). Removing them costs a
  // wedge of h^2/2 at a front sliding on a wall, where the front particle stays connected through its
  // other elements.
  // With the advected domain (previous != nullptr) a meniscus element is only ever there because the fluid
  // was: new ones are not added (meshing/remesh.cpp), and existing ones go by the separation test.
  const bool meniscus_filter = previous == nullptr || previous->empty();
  size_t kept = 0;
  bool removed = false;
  for (size_t e = 0; e < tri_.size(); ++e) {
    int walls = 0, free_fluid = 0;
    for (Index i : tri_[e]) {
      walls += kind_[i] != ParticleKind::Fluid;
      free_fluid += kind_[i] == ParticleKind::Fluid && free_[i];
    }
    if ((meniscus_filter && walls == 2 && free_fluid == 1) || element_area(state_.x, static_cast<Index>(e)) < flat_fraction_ * h_ * h_ ||
        (ghost_particles_ > 0 && crosses_structure(static_cast<Index>(e)))) {
      removed = true;
      continue;
    }
    tri_[kept++] = tri_[e];
  }
  tri_.resize(kept);
  if (removed) {
    std::vector<char> walls(n(), 0);
    for (Index i = 0; i < n(); ++i) walls[i] = kind_[i] != ParticleKind::Fluid;
    mark_free_surface(walls);
  }
}

void FluidModel::mark_free_surface(const std::vector<char>& on_wall) {
  const Index np = n();
  std::vector<std::pair<Index, Index>> edges;
  edges.reserve(3 * tri_.size());
  connected_.assign(np, 0);
  for (const auto& t : tri_)
    for (int k = 0; k < 3; ++k) {
      connected_[t[k]] = 1;
      edges.push_back(std::minmax(t[k], t[(k + 1) % 3]));
    }
  std::sort(edges.begin(), edges.end());
  free_.assign(np, 0);
  for (size_t k = 0; k < edges.size(); ++k) {
    const bool shared = (k + 1 < edges.size() && edges[k + 1] == edges[k]) || (k > 0 && edges[k - 1] == edges[k]);
    if (shared || (on_wall[edges[k].first] && on_wall[edges[k].second])) continue;
    for (Index i : {edges[k].first, edges[k].second})
      if (kind_[i] == ParticleKind::Fluid) free_[i] = 1;
  }
}

bool FluidModel::remove_close_particles() {
  // Particles pressed together (impacts, the wall) make near-flat elements that invert within a step.
  // Of a fluid-fluid pair closer than close_fraction * h one particle goes (meshing picks it); a fluid
  // particle closer than that to a wall particle goes. The fluid area is measured on the elements, so
  // the mass this removes shows in the area drift.
  if (close_fraction_ <= 0) return false;
  const Index np = n();
  std::vector<Vec2> pts(np);
  for (Index i = 0; i < np; ++i) pts[i] = state_.x.segment<2>(2 * i);
  std::vector<char> drop(np, 0);
  for (Index i : meshing::close_fluid_particles(pts, kind_, hvec_, tri_, close_fraction_)) drop[i] = 1;
  for (const auto& t : tri_)
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k], b = t[(k + 1) % 3];
      const bool fa = kind_[a] == ParticleKind::Fluid, fb = kind_[b] == ParticleKind::Fluid;
      if (fa == fb) continue;
      if ((pts[a] - pts[b]).norm() < close_fraction_ * h_) drop[fa ? a : b] = 1;
    }
  return drop_particles(drop);
}

bool FluidModel::drop_particles(const std::vector<char>& drop) {
  const Index np = n();
  Index kept = 0;
  std::vector<Index>& renumber = renumber_;
  renumber.assign(np, -1);
  for (Index i = 0; i < np; ++i) {
    if (drop[i]) continue;
    renumber[i] = kept;
    kind_[kept] = kind_[i];
    hvec_[kept] = hvec_[i];
    state_.x.segment<2>(2 * kept) = state_.x.segment<2>(2 * i);
    state_.v.segment<2>(2 * kept) = state_.v.segment<2>(2 * i);
    state_.a.segment<2>(2 * kept) = state_.a.segment<2>(2 * i);
    X0_.segment<2>(2 * kept) = X0_.segment<2>(2 * i);
    p_[kept] = p_[i];
    ++kept;
  }
  if (kept == np) return false;
  size_t kept_elements = 0;
  for (const auto& t : tri_) {
    if (renumber[t[0]] < 0 || renumber[t[1]] < 0 || renumber[t[2]] < 0) continue;
    tri_[kept_elements++] = {renumber[t[0]], renumber[t[1]], renumber[t[2]]};
  }
  tri_.resize(kept_elements);
  kind_.resize(kept);
  hvec_.resize(kept);
  state_.x.conservativeResize(2 * kept);
  state_.v.conservativeResize(2 * kept);
  state_.a.conservativeResize(2 * kept);
  X0_.conservativeResize(2 * kept);
  p_.conservativeResize(kept);
  return true;
}

bool FluidModel::drop_outside_domain() {
  // Fluid particles that left the domain box (walls and initial fluid, enlarged by domain_margin times the
  // larger side) are gone: a jet that falls off the end of a floor would otherwise fly forever. The box is
  // open on the side gravity points away from: a splash thrown above the walls falls back.
  if (domain_lo_.x() > domain_hi_.x()) return false;
  const Vec2 g = ctx_.gravity;
  const Vec2 lo(g.x() > 0 ? -std::numeric_limits<double>::infinity() : domain_lo_.x(),
                g.y() > 0 ? -std::numeric_limits<double>::infinity() : domain_lo_.y());
  const Vec2 hi(g.x() < 0 ? std::numeric_limits<double>::infinity() : domain_hi_.x(),
                g.y() < 0 ? std::numeric_limits<double>::infinity() : domain_hi_.y());
  std::vector<char> drop(n(), 0);
  bool any = false;
  Index fluid_left = 0;
  for (Index i = 0; i < n(); ++i) {
    if (kind_[i] != ParticleKind::Fluid) continue;
    const Vec2 q = state_.x.segment<2>(2 * i);
    if (q.x() < lo.x() || q.y() < lo.y() || q.x() > hi.x() || q.y() > hi.y()) {
      drop[i] = 1;
      any = true;
    } else {
      ++fluid_left;
    }
  }
  if (!any) return false;
  if (fluid_left == 0)
    throw SolverError("body '" + name_ + "': all fluid particles left the domain box by t = " + std::to_string(t_new_));
  // The fluid that left is gone: its share of the last mesh (A_e / 3 per dropped particle of each element)
  // leaves the reference area too, so that the volume correction does not make it up elsewhere.
  for (Index e = 0; e < static_cast<Index>(tri_.size()); ++e)
    for (Index i : tri_[e])
      if (drop[i]) area_left_ += element_area(state_.x, e) / 3.0;
  area_ref_ = area_initial_ - area_left_;
  return drop_particles(drop);
}

void FluidModel::restore_area() {
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
  const Index np = n();
  // Only the surface of the bulk moves: a free-surface particle of an element with an interior fluid
  // particle. Films, jets and drops (elements of free-surface particles only) keep their positions: their
  // continuity rows are not solved (p = 0 on the free surface), and a push along their thin outline would
  // accumulate at their tips (the front of a dam break runs ahead by a film).
  std::vector<char> movable = beside_interior_fluid();
  const std::vector<char> at_wall = in_element_with([&](Index i) { return kind_[i] != ParticleKind::Fluid; });
  for (Index i = 0; i < np; ++i)
    movable[i] = movable[i] && kind_[i] == ParticleKind::Fluid && free_[i] && !at_wall[i];
  const auto area2 = [](const Vec2& a, const Vec2& b, const Vec2& c) {   // twice the signed area
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  Vec g(2 * np);
  std::vector<double> lumped(np);   // lumped areas (the particles' masses / rho): the potential energy
                                    // the correction moves is counted (probe volume_correction_energy)
  for (int pass = 0; pass < 2; ++pass) {
    double area = 0;
    g.setZero();
    std::fill(lumped.begin(), lumped.end(), 0.0);
    for (Index e = 0; e < static_cast<Index>(tri_.size()); ++e) {
      const auto& t = tri_[e];
      const Vec2 xa = state_.x.segment<2>(2 * t[0]), xb = state_.x.segment<2>(2 * t[1]),
                 xc = state_.x.segment<2>(2 * t[2]);
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
        gmax = std::max(gmax, g.segment<2>(2 * i).norm() / hvec_[i]);
      }
      if (!(gg > 0)) return;
      lambda = error / gg;
      if (std::abs(lambda) * gmax > 0.05) lambda = std::copysign(0.05 / gmax, lambda);
      bool frozen = false;
      for (const auto& t : tri_) {
        if (!(movable[t[0]] || movable[t[1]] || movable[t[2]])) continue;
        Vec2 y[3];
        for (int k = 0; k < 3; ++k)
          y[k] = state_.x.segment<2>(2 * t[k]) + (movable[t[k]] ? lambda : 0.0) * g.segment<2>(2 * t[k]);
        const Vec2 xa = state_.x.segment<2>(2 * t[0]), xb = state_.x.segment<2>(2 * t[1]),
                   xc = state_.x.segment<2>(2 * t[2]);
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
      state_.x.segment<2>(2 * i) += lambda * g.segment<2>(2 * i);
      correction_energy_ -= rho_ * lumped[i] * ctx_.gravity.dot(lambda * g.segment<2>(2 * i));
    }
  }
}

void FluidModel::append_particle(const Vec2& x, const Vec2& v, const Vec2& a, double p, double h) {
  const Index k = n();
  state_.x.conservativeResize(2 * k + 2);
  state_.v.conservativeResize(2 * k + 2);
  state_.a.conservativeResize(2 * k + 2);
  X0_.conservativeResize(2 * k + 2);
  p_.conservativeResize(k + 1);
  state_.x.segment<2>(2 * k) = x;
  X0_.segment<2>(2 * k) = x;
  state_.v.segment<2>(2 * k) = v;
  state_.a.segment<2>(2 * k) = a;
  p_[k] = p;
  kind_.push_back(ParticleKind::Fluid);
  hvec_.push_back(h);
}

bool FluidModel::insert_particles() {
  // Where the flow stretches the particle distribution, elements grow until the alpha test deletes them
  // and the fluid tears; a particle at the centroid of every element larger than insert_factor * h^2
  // (with the element's mean velocity, acceleration and pressure) keeps the spacing near h.
  if (insert_factor_ <= 0) return false;
  const Index np = n();
  std::vector<Vec2> pts(np);
  for (Index i = 0; i < np; ++i) pts[i] = state_.x.segment<2>(2 * i);
  const auto big = meshing::oversized_elements(pts, hvec_, tri_, insert_factor_);
  if (big.empty()) return false;
  for (Index e : big) {
    const auto& t = tri_[e];
    Vec2 x = Vec2::Zero(), v = Vec2::Zero(), a = Vec2::Zero();
    double p = 0, hh = 0;
    for (Index i : t) {
      x += state_.x.segment<2>(2 * i) / 3.0;
      v += state_.v.segment<2>(2 * i) / 3.0;
      a += state_.a.segment<2>(2 * i) / 3.0;
      p += p_[i] / 3.0;
      hh += hvec_[i] / 3.0;
    }
    append_particle(x, v, a, p, hh);
  }
  return true;
}

void FluidModel::set_wall_motion(double t, Vec& v, Vec& a) const {
  for (const auto& w : walls_) {
    if (!w.fn) continue;
    const Vec2 vw = w.velocity_at(t), aw = w.acceleration_at(t);
    for (Index j : w.particles) {
      v.segment<2>(2 * j) = vw;
      a.segment<2>(2 * j) = aw;
    }
  }
}

std::vector<char> FluidModel::in_element_with(const std::function<bool(Index)>& pred) const {
  std::vector<char> flag(static_cast<size_t>(n()), 0);
  for (const auto& t : tri_)
    if (pred(t[0]) || pred(t[1]) || pred(t[2]))
      for (Index i : t) flag[i] = 1;
  return flag;
}

std::vector<char> FluidModel::beside_interior_fluid() const {
  return in_element_with([&](Index i) { return kind_[i] == ParticleKind::Fluid && !free_[i]; });
}

void FluidModel::set_dirichlet() {
  const Index np = n();
  fixed_.assign(3 * np, 0);
  for (Index i = 0; i < np; ++i) {
    if (kind_[i] != ParticleKind::Fluid) fixed_[3 * i] = fixed_[3 * i + 1] = 1;
    const bool free_surface = free_[i] && p_free_dirichlet_;
    if (!connected_[i] || free_surface) fixed_[3 * i + 2] = 1;
  }
  for (const auto& [i, c] : slip_) fixed_[3 * i + c] = 1;
  // Dry wall particles: a wall particle in no element with an interior (non-free-surface) fluid particle
  // is above or beside the free surface (a meniscus element between a surface particle and the wall);
  // its pressure is the free-surface one. Left unknown, its continuity row sees only gravity and builds a
  // suction that pulls the surface particles up the wall (spurious currents in a tank at rest).
  if (p_free_dirichlet_ && remesh_) {
    const std::vector<char> wet = beside_interior_fluid();
    for (Index i = 0; i < np; ++i)
      if (kind_[i] != ParticleKind::Fluid && !wet[i]) fixed_[3 * i + 2] = 1;
  }
}

// ------------------------------------------------------------------------------------------ lifecycle

void FluidModel::initialize() {
  const auto t0 = Clock::now();
  const Index np = n();
  if (remesh_ && detection_ != meshing::DomainDetection::Alpha) {
    // The initial domain is the regions themselves: the Delaunay elements whose centroid lies in them (with
    // the separation test), none outside (a level set of zero band). The alpha shape would cut the corners
    // where the surface meets a wall, which the advected domain would then keep filling and emptying.
    meshing::PreviousDomain regions(std::move(region_triangles_), {});
    const auto keep = detection_;
    const double band = level_set_band_;
    detection_ = meshing::DomainDetection::LevelSet;
    level_set_band_ = 0.0;
    remesh_now(&regions);
    detection_ = keep;
    level_set_band_ = band;
    added_outside_ = separated_ = 0;
  } else if (remesh_) {
    remesh_now();
  } else {
    // Free surface of the fixed mesh: nodes of unshared edges that do not lie on a wall.
    std::vector<char> on_wall(np, 0);
    for (const auto& [i, c] : slip_) on_wall[i] = 1;
    mark_free_surface(on_wall);
  }
  std::vector<std::array<Vec2, 3>>().swap(region_triangles_);   // only the initial domain needs them
  area_ref_ = mesh_area();
  area_remesh_ = area_end_ = area_initial_ = area_ref_;
  n_initial_ = np;
  double ymin = 1e300, ymax = -1e300;
  for (Index i = 0; i < np; ++i)
    if (kind_[i] == ParticleKind::Fluid) {
      ymin = std::min(ymin, state_.x[2 * i + 1]);
      ymax = std::max(ymax, state_.x[2 * i + 1]);
    }
  // Pressure scale of the convergence test: hydrostatic, initial and dynamic (rho v^2: a flow without gravity).
  double v2 = 0;
  for (Index i = 0; i < np; ++i) v2 = std::max(v2, state_.v.segment<2>(2 * i).squaredNorm());
  p_scale_ = std::max({rho_ * ctx_.gravity.norm() * (ymax - ymin), p_.cwiseAbs().maxCoeff(), rho_ * v2, 1e-12});
  // Initial acceleration from the momentum equation with the lumped mass, the initial pressure (zero on
  // the free surface, as the solver will impose) and the initial velocity. An inconsistent a0 excites the
  // period-2 pressure oscillation of the trapezoidal rule on this index-2 system (a hydrostatic column
  // started with a0 = g alternates between 0 and twice the hydrostatic pressure).
  set_dirichlet();
  for (Index i = 0; i < np; ++i)
    if (fixed_[3 * i + 2]) p_[i] = 0.0;
  // The element kernel's momentum rows with zero acceleration are the viscous, pressure and gravity
  // forces r = f_visc - f_p - m g; with the lumped mass m_i, a0_i = -r_i / m_i.
  Vec force = Vec::Zero(2 * np), mass = Vec::Zero(np);
  const Vec zero = Vec::Zero(2 * np);
  for (Index e = 0; e < static_cast<Index>(tri_.size()); ++e) {
    Eigen::Matrix<double, 9, 1> r;
    Eigen::Matrix<double, 9, 9> K;
    double i2 = 0, g2 = 0;
    if (!pspg_element(element_input(e, state_.x, state_.v, zero, 0.0, 0.0), r, K, i2, g2)) continue;
    const double m = rho_ * element_area(state_.x, e) / 3.0;
    for (int k = 0; k < 3; ++k) {
      force.segment<2>(2 * tri_[e][k]) -= r.segment<2>(3 * k);
      mass[tri_[e][k]] += m;
    }
  }
  for (Index i = 0; i < np; ++i) {
    if (kind_[i] != ParticleKind::Fluid) continue;
    state_.a.segment<2>(2 * i) = mass[i] > 0 ? Vec2(force.segment<2>(2 * i) / mass[i]) : ctx_.gravity;
  }
  for (const auto& [i, c] : slip_) state_.a[2 * i + c] = state_.v[2 * i + c] = 0.0;
  set_wall_motion(0.0, state_.v, state_.a);
  times_.assembly += seconds_since(t0);
}

void FluidModel::predict(double t_new, double dt) {
  auto t0 = Clock::now();
  // A retry of a failed step (the driver calls predict again with a smaller dt): start again from the
  // step's initial pressures. The failed attempt left its own in p_, and taking them as the start of the
  // retry compounded the failure (a projection velocity growing like 1/dt at every halving).
  if (step_open_) p_ = p_old_;
  step_open_ = true;
  t_new_ = t_new;
  dt_ = dt;
  if (remesh_ && solved_once_) remesh_step();
  times_.remesh += seconds_since(t0);
  t0 = Clock::now();
  solved_once_ = true;
  const Index np = n();
  conn_.resize(3 * tri_.size());
  for (size_t e = 0; e < tri_.size(); ++e)
    for (int k = 0; k < 3; ++k) conn_[3 * e + k] = tri_[e][k];
  if (scheme_ == "monolithic_pspg") {
    pattern_ = ElementPattern(conn_, 3, np, 3);
    J_ = pattern_.pattern();
  } else {
    poisson_pattern_ = ElementPattern(conn_, 3, np, 1);
    poisson_ = poisson_pattern_.pattern();
    if (viscous_implicit()) viscous_ = poisson_;
  }
  set_dirichlet();
  area_remesh_ = mesh_area();
  // Volume correction "source": a uniform source in the continuity equation, div v = -(A - A_ref)/(A_ref T),
  // that closes the area error of remeshing (alpha shape, inserted/removed particles) over the relaxation
  // time T. The pressure it needs scales like rho L^2 (error)/T^2, so T must stay long compared with dt;
  // then it cannot keep up with a splash (and contracting thin regions lets the alpha shape close more
  // elements): the default is the "surface" correction (restore_area) instead.
  c_vol_ = volume_correction_ == "source" && area_ref_ > 0
               ? (area_remesh_ - area_ref_) / (area_ref_ * relax_time_)
               : 0.0;

  if (scheme_ == "monolithic_pspg") integrator_->begin_step(state_, dt);
  p_old_ = p_;
  // A new mesh: new matrices. Re-solves of the step (restart_step) keep the factorizations (the monolithic
  // scheme's Jacobian of the first pass, the fractional step's matrices, which depend on the mesh only).
  iter_in_step_ = 0;
  step_factorized_ = false;
  contact_ = false;
  for (const auto& t : tri_)
    for (Index i : t) contact_ = contact_ || is_ghost(i);
  start_iterations();
  times_.assembly += seconds_since(t0);
}

void FluidModel::start_iterations() {
  const Index np = n();
  p_ = p_old_;
  x_ = state_.x + dt_ * state_.v;  // constant-velocity predictor
  for (const auto& w : walls_)  // prescribed wall motion
    for (Index j : w.particles) x_.segment<2>(2 * j) = X0_.segment<2>(2 * j) + w.offset(t_new_);
  for (const auto& [i, c] : slip_) x_[2 * i + c] = state_.x[2 * i + c];
  if (ghost_x_.size() > 0)
    for (size_t g = 0; g < ghost_index_.size(); ++g)
      if (!ghost_merged_[g]) x_.segment<2>(2 * ghost_index_[g]) = ghost_x_.segment<2>(2 * g);
  for (Index i = 0; i < np; ++i)
    if (fixed_[3 * i + 2]) p_[i] = 0.0;
  last_dx_ = last_dp_ = prev_dx_ = std::numeric_limits<double>::infinity();
}

// ------------------------------------------------------------------------------------------ ghosts

int FluidModel::add_ghosts(const std::vector<Vec2>& points, const std::vector<std::pair<Index, Index>>& adjacent) {
  if (!remesh_) throw std::invalid_argument("body '" + name_ + "': ghost particles need \"remesh\": true");
  if (ghost_particles_ > 0 || !ghost_index_.empty())
    throw std::invalid_argument("body '" + name_ + "': only one coupled structure per fluid in this version");
  Index n_wall = 0;
  while (n_wall < n() && kind_[n_wall] == ParticleKind::Wall) ++n_wall;
  ghost_begin_ = n_wall;
  // Ghosts on a wall particle are merged with it; the others become new particles after the walls.
  std::vector<Vec2> fresh;
  std::vector<Index> local(points.size(), -1);
  int merged = 0;
  for (size_t g = 0; g < points.size(); ++g) {
    Index found = -1;
    for (Index j = 0; j < n_wall && found < 0; ++j)
      if ((state_.x.segment<2>(2 * j) - points[g]).norm() < 0.25 * h_) found = j;
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
  for (const auto& [a, b] : adjacent) {
    if (local[a] < 0 || local[b] < 0) continue;
    ghost_neighbours_[local[a]].push_back(n_wall + local[b]);
    ghost_neighbours_[local[b]].push_back(n_wall + local[a]);
  }
  // Rebuild the cloud: walls, ghosts, then the fluid particles not within h/2 of a ghost.
  const Index np = n();
  std::vector<Index> order;
  for (Index i = 0; i < n_wall; ++i) order.push_back(i);
  for (Index i = n_wall; i < np; ++i) {
    bool near = false;
    for (const auto& q : fresh) near = near || (state_.x.segment<2>(2 * i) - q).norm() < 0.5 * h_;
    if (!near) order.push_back(i);
  }
  const Index nn = static_cast<Index>(order.size() + fresh.size());
  std::vector<ParticleKind> kind(nn);
  std::vector<double> hv(nn, h_);
  Vec x(2 * nn), v = Vec::Zero(2 * nn), a = Vec::Zero(2 * nn), X0(2 * nn), p = Vec::Zero(nn);
  Index k = 0;
  auto copy = [&](Index i) {
    kind[k] = kind_[i];
    hv[k] = hvec_[i];
    x.segment<2>(2 * k) = state_.x.segment<2>(2 * i);
    v.segment<2>(2 * k) = state_.v.segment<2>(2 * i);
    a.segment<2>(2 * k) = state_.a.segment<2>(2 * i);
    X0.segment<2>(2 * k) = X0_.segment<2>(2 * i);
    p[k] = p_[i];
    ++k;
  };
  for (Index i = 0; i < n_wall; ++i) copy(i);
  for (const auto& q : fresh) {
    // The ghost starts with the initial pressure of the nearest fluid particle (the fractional step
    // corrects pressures by increments, so a ghost started at zero would keep a wrong load for many steps).
    kind[k] = ParticleKind::Ghost;
    x.segment<2>(2 * k) = q;
    X0.segment<2>(2 * k) = q;
    double best = std::numeric_limits<double>::infinity();
    for (Index i = n_wall; i < np; ++i) {
      const double d = (state_.x.segment<2>(2 * i) - q).squaredNorm();
      if (kind_[i] == ParticleKind::Fluid && d < best) {
        best = d;
        p[k] = p_[i];
      }
    }
    ++k;
  }
  for (size_t j = static_cast<size_t>(n_wall); j < order.size(); ++j) copy(order[j]);
  kind_ = std::move(kind);
  hvec_ = std::move(hv);
  state_.x = std::move(x);
  state_.v = std::move(v);
  state_.a = std::move(a);
  X0_ = std::move(X0);
  p_ = std::move(p);
  // The domain box holds the structure's boundary too.
  if (domain_lo_.x() <= domain_hi_.x()) {
    const double margin = domain_margin_ * (domain_hi_ - domain_lo_).maxCoeff() / (1 + 2 * domain_margin_);
    for (const auto& q : points) {
      domain_lo_ = domain_lo_.cwiseMin(q - Vec2::Constant(margin));
      domain_hi_ = domain_hi_.cwiseMax(q + Vec2::Constant(margin));
    }
  }
  ghost_force_ = Vec::Zero(2 * static_cast<Index>(points.size()));
  return merged;
}

void FluidModel::set_ghost_motion(const Vec& x, const Vec& v, const Vec& a) {
  const Index ng = static_cast<Index>(ghost_index_.size());
  if (x.size() != 2 * ng || v.size() != 2 * ng || a.size() != 2 * ng)
    throw SolverError("body '" + name_ + "': ghost motion of the wrong size");
  ghost_x_ = x;
  ghost_v_ = v;
  ghost_a_ = a;
  if (x_.size() == state_.x.size())
    for (Index g = 0; g < ng; ++g)
      if (!ghost_merged_[g]) x_.segment<2>(2 * ghost_index_[g]) = x.segment<2>(2 * g);
}

void FluidModel::set_ghost_rates(Vec& v, Vec& a) const {
  if (ghost_v_.size() == 0) return;
  for (size_t g = 0; g < ghost_index_.size(); ++g) {
    if (ghost_merged_[g]) continue;
    v.segment<2>(2 * ghost_index_[g]) = ghost_v_.segment<2>(2 * g);
    a.segment<2>(2 * ghost_index_[g]) = ghost_a_.segment<2>(2 * g);
  }
}

bool FluidModel::crosses_structure(Index e) const {
  const auto& t = tri_[e];
  for (int k = 0; k < 3; ++k) {
    const Index i = t[k], j = t[(k + 1) % 3];
    if (!is_ghost(i) || !is_ghost(j)) continue;
    const auto& nb = ghost_neighbours_[i - ghost_begin_];
    if (std::find(nb.begin(), nb.end(), j) == nb.end()) return true;
  }
  return false;
}

IterationReport FluidModel::solve_iteration() {
  return scheme_ == "monolithic_pspg" ? newton_iteration() : fractional_step();
}

IterationReport FluidModel::newton_iteration() {
  auto t0 = Clock::now();
  const Index np = n();
  EvalPoint ev = integrator_->kinematics(x_);
  // Moving walls: their particles' velocity and acceleration are those of the prescribed motion (from the
  // trapezoidal rule they would alternate around it after the jump of the wall's velocity at the start,
  // and the pressure in the tank then grows step after step).
  set_wall_motion(ev.t, ev.v, ev.a);
  set_ghost_rates(ev.v, ev.a);
  const TangentCoefficients cf = integrator_->coefficients();
  const Vec2 g = ctx_.gravity;  // ballistic particles below
  Vec R = Vec::Zero(3 * np);
  double* jv = J_.valuePtr();
  std::fill(jv, jv + J_.nonZeros(), 0.0);
  std::vector<char> has_mass(np, 0);
  double inertia2 = 0, gravity2 = 0;
  std::string failure;

  const Index ne = static_cast<Index>(tri_.size());
  // One parallel loop over all elements with atomic additions (no colour barriers: on a loaded 2-core
  // machine each OpenMP barrier of busy-waiting threads can cost a time slice).
#pragma omp parallel for schedule(static) if (ne >= 2000) reduction(+ : inertia2, gravity2)
    for (Index e = 0; e < ne; ++e) {
      const auto& t = tri_[e];
      const PspgElementInput in = element_input(e, ev.x, ev.v, ev.a, cf.c_m, cf.c_c);
      Eigen::Matrix<double, 9, 1> r;
      Eigen::Matrix<double, 9, 9> K;
      double i2 = 0, g2 = 0;
      if (!pspg_element(in, r, K, i2, g2)) {
        // Turned over by a structure's boundary sliding past another prescribed particle (see
        // moving_boundary_pair): left out of this step, removed by the next remesh.
        if (moving_boundary_pair(e)) continue;
#pragma omp critical(lagfsi_fluid_failure)
        failure = "element " + std::to_string(e) + " (particles " + std::to_string(t[0]) + ", " +
                  std::to_string(t[1]) + ", " + std::to_string(t[2]) + ") inverted during the step at t = " +
                  std::to_string(t_new_) + " (area " + std::to_string(element_area(ev.x, e)) + ")";
        continue;
      }
      inertia2 += i2;
      gravity2 += g2;
      for (int a = 0; a < 3; ++a) {
        for (int c = 0; c < 3; ++c) {
#pragma omp atomic
          R[3 * t[a] + c] += r[3 * a + c];
        }
        has_mass[t[a]] = 1;
      }
      const int* sc = pattern_.scatter(e);
      for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) {
#pragma omp atomic
          jv[sc[j * 9 + i]] += K(i, j);
        }
    }
  if (!failure.empty()) throw SolverError("body '" + name_ + "': " + failure);

  // Particles in no element fly ballistically: m (a - g) = 0 with a nominal mass.
  const double m0 = rho_ * h_ * h_;
  const int* op = J_.outerIndexPtr();
  const int* ip = J_.innerIndexPtr();
  auto diag = [&](Index dof) -> double& {
    const int* pos = std::lower_bound(ip + op[dof], ip + op[dof + 1], dof);
    return jv[pos - ip];
  };
  for (Index i = 0; i < np; ++i) {
    if (has_mass[i] || kind_[i] != ParticleKind::Fluid) continue;
    for (int c = 0; c < 2; ++c) {
      R[3 * i + c] = m0 * (ev.a[2 * i + c] - g[c]);
      diag(3 * i + c) += cf.c_m * m0;
    }
  }
  // Dirichlet: rows and columns of prescribed dofs become identity. Pressure columns are scaled by
  // s_p = 3 rho h c_m (p = s_p p^), which brings the pressure blocks to the size of the momentum block:
  // unscaled, the PSPG diagonal (tau/rho ~ 1e-7) is far below the pivoting threshold of the sparse LU,
  // whose off-diagonal pivots then destroy the fill-reducing ordering (4-5x slower factorizations).
  const double sp = 3.0 * rho_ * h_ * cf.c_m;
  for (int k = 0; k < J_.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(J_, k); it; ++it) {
      if (fixed_[it.row()] || fixed_[it.col()])
        it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
      else if (k % 3 == 2)
        it.valueRef() *= sp;
    }
  // Forces on the ghost particles: the reactions of their prescribed momentum rows, sign flipped (the
  // residual there is the force the structure applies to the fluid).
  for (size_t gi = 0; gi < ghost_index_.size(); ++gi)
    for (int c = 0; c < 2; ++c)
      ghost_force_[2 * gi + c] = ghost_merged_[gi] ? 0.0 : -R[3 * ghost_index_[gi] + c];
  // The force each wall or ghost particle applies to the fluid (its prescribed momentum row's residual):
  // the boundary work of the energy balance.
  if (energy_probes_) {
    boundary_force_.resize(2 * n_boundary_particles());
    for (Index i = 0; i < boundary_force_.size() / 2; ++i)
      for (int c = 0; c < 2; ++c) boundary_force_[2 * i + c] = R[3 * i + c];
  }
  double rm2 = 0;
  for (Index i = 0; i < 3 * np; ++i) {
    if (fixed_[i]) R[i] = 0.0;
    else if (i % 3 != 2) rm2 += R[i] * R[i];
  }
  IterationReport rep;
  rep.residual = std::sqrt(rm2);
  rep.residual_ref = std::max(std::sqrt(inertia2), std::sqrt(gravity2));
  rep.increment = last_dx_;
  rep.increment_ref = h_;
  if (!std::isfinite(rep.residual)) throw SolverError("body '" + name_ + "': non-finite residual");
  times_.assembly += seconds_since(t0);
  // Converged: the last corrections of positions and pressures are below tolerance; or the momentum
  // residual is at round-off (1e-10 of the force scale) and the corrections stopped decreasing (the
  // frozen-geometry tangent converges linearly, and in the scaled pressure unknowns round-off keeps the
  // pressure corrections of a few particles from ever reaching tol * p_scale).
  const bool stalled = last_dx_ > 0.5 * prev_dx_ && rep.residual <= 1e-10 * rep.residual_ref && last_dx_ <= 1e-3 * h_;
  if ((last_dx_ <= tol_ * h_ && last_dp_ <= tol_ * p_scale_) || stalled) {
    rep.converged = true;
    return rep;
  }

  t0 = Clock::now();
  if (refactor_every_ == 0 ? iter_in_step_ == 0 : iter_in_step_ % refactor_every_ == 0) {
    try {
      solver_->factorize(J_);
    } catch (const SolverError& e) {
      throw SolverError("body '" + name_ + "': " + e.what());
    }
  }
  ++iter_in_step_;
  times_.factorization += seconds_since(t0);
  t0 = Clock::now();
  Vec d;
  solver_->solve(-R, d);
  times_.solve += seconds_since(t0);
  prev_dx_ = last_dx_;
  last_dx_ = last_dp_ = 0;
  for (Index i = 0; i < np; ++i) {
    x_[2 * i] += d[3 * i];
    x_[2 * i + 1] += d[3 * i + 1];
    const double dp = fixed_[3 * i + 2] ? 0.0 : sp * d[3 * i + 2];
    p_[i] += dp;
    last_dx_ = std::max({last_dx_, std::abs(d[3 * i]), std::abs(d[3 * i + 1])});
    last_dp_ = std::max(last_dp_, std::abs(dp));
  }
  if (!x_.allFinite() || !p_.allFinite()) throw SolverError("body '" + name_ + "': non-finite solution");
  if (std::getenv("LAGFSI_DEBUG_NEWTON")) {  // developer aid: one line per Newton iteration on stderr
    Index worst = 0;
    for (Index i = 0; i < np; ++i)
      if (std::abs(d[3 * i]) + std::abs(d[3 * i + 1]) > std::abs(d[3 * worst]) + std::abs(d[3 * worst + 1])) worst = i;
    std::fprintf(stderr, "  t=%.6g res=%.3e ref=%.3e dx=%.3e (h %.3e) dp=%.3e (p %.3e) worst %d kind %d free %d\n", t_new_,
                 rep.residual, rep.residual_ref, last_dx_, h_, last_dp_, p_scale_, worst, int(kind_[worst]),
                 int(free_[worst]));
  }
  return rep;
}

void FluidModel::account_energy() {
  // On the step's mesh at x_n (lumped masses m_i = sum rho A/3, walls and ghosts included: their share of
  // the fluid moves with them): work of gravity sum m_i g . (x_{n+1} - x_n) and viscous dissipation
  // dt sum_e 2 mu A eps(v):eps(v) of the step's velocity (v_{n+1} for the fractional step, the mean of
  // v_n and v_{n+1} for the trapezoidal rule).
  const Index ne = static_cast<Index>(tri_.size());
  Vec v_end = scheme_ == "monolithic_pspg" ? Vec(2.0 / dt_ * (x_ - state_.x) - state_.v) : v_new_;
  const Vec v = scheme_ == "monolithic_pspg" ? Vec(0.5 * (state_.v + v_end)) : v_end;
  double gw = 0, diss = 0;
  for (Index e = 0; e < ne; ++e) {
    const auto& t = tri_[e];
    const double A = element_area(state_.x, e);
    if (!(A > 0)) continue;
    Mat2 L = Mat2::Zero();
    for (int k = 0; k < 3; ++k) {
      const Vec2& p = state_.x.segment<2>(2 * t[(k + 1) % 3]);
      const Vec2& q = state_.x.segment<2>(2 * t[(k + 2) % 3]);
      const Vec2 grad = Vec2(p.y() - q.y(), q.x() - p.x()) / (2 * A);
      L += v.segment<2>(2 * t[k]) * grad.transpose();
      gw += rho_ * A / 3.0 * ctx_.gravity.dot(x_.segment<2>(2 * t[k]) - state_.x.segment<2>(2 * t[k]));
    }
    if (mu_ > 0 && !inviscid_element(e)) {
      const Mat2 eps = 0.5 * (L + L.transpose());
      diss += dt_ * 2.0 * mu_ * A * (eps.array() * eps.array()).sum();
    }
  }
  gravity_work_ += gw;
  dissipation_ += diss;
  // Work of the moving walls and ghosts on the fluid: the mean of the step's start and end forces times
  // the step's displacement (their indices are stable: walls, then ghosts, come first in the cloud).
  const Index nb = std::min<Index>(static_cast<Index>(boundary_force_.size() / 2), n_boundary_particles());
  if (boundary_force_prev_.size() != boundary_force_.size()) boundary_force_prev_ = boundary_force_;
  for (Index i = 0; i < nb; ++i)
    boundary_work_ += 0.5 * (boundary_force_prev_.segment<2>(2 * i) + boundary_force_.segment<2>(2 * i))
                          .dot(x_.segment<2>(2 * i) - state_.x.segment<2>(2 * i));
  boundary_force_prev_ = boundary_force_;
}

Index FluidModel::n_boundary_particles() const {
  Index nb = 0;
  while (nb < n() && kind_[nb] != ParticleKind::Fluid) ++nb;
  return nb;
}

void FluidModel::keep_inside_walls(const Vec& x_start) {
  // A fluid particle in no element with a wall's particles (a drop flying ballistically) is not held by
  // the wall, and a fast one may pass between the particles of its element: in one step it can cross the
  // wall (a drop at 4 m/s moves 0.8 h a step at h = 5 mm, dt = 1 ms). Without this check the drops were
  // lost through the walls and dropped at the domain box (1.3 % of the fluid in elastic_obstacle_walhorn by
  // 1 s). A particle that ends more than 0.5 h (h if held, below) beyond a wall segment is put back 0.05 h
  // on the segment's fluid side, and loses the velocity component into the wall (an inelastic impact), if
  //  - the segment has a fluid side (the initial fluid's) and the particle started less than that
  //    beyond it (within the segment's span), or
  //  - its path x_n -> x_{n+1} crossed the segment (the side it came from is then the fluid side).
  // A particle in an element with a wall particle is held by the mesh, and its excursions across the wall
  // line of up to one spacing (a film sliding on the floor between the no-slip particles) are the
  // discretization's: only a held particle more than h beyond the wall is put back (putting back the film's
  // particles at 0.25 h made the film at a dam-break toe run ahead: dam_break_floor front RMS 0.21 -> 0.50;
  // 0.5 h leaves that film alone).
  if (!remesh_) return;
  const std::vector<char> held = in_element_with([&](Index i) { return kind_[i] == ParticleKind::Wall; });
  const auto cross = [](const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); };
  for (Index i = 0; i < n(); ++i) {
    if (kind_[i] != ParticleKind::Fluid) continue;
    const Vec2 p0 = x_start.segment<2>(2 * i);
    Vec2 p1 = state_.x.segment<2>(2 * i);
    const double tol = (held[i] ? 1.0 : 0.5) * hvec_[i];
    for (const auto& w : walls_) {
      const Vec2 off = w.offset(t_new_);
      for (size_t k = 0; k + 1 < w.polyline.size(); ++k) {
        const Vec2 a = w.polyline[k] + off, b = w.polyline[k + 1] + off, e = b - a;
        Vec2 nrm = Vec2(-e.y(), e.x()).normalized();
        double u;  // where the particle goes back, along the segment
        if (w.fluid_side[k] != 0) {
          nrm *= w.fluid_side[k];
          u = (p1 - a).dot(e) / e.squaredNorm();
          if (!(u >= 0 && u <= 1) || nrm.dot(p1 - a) >= -tol || nrm.dot(p0 - a) <= -tol) continue;
        } else {
          const Vec2 d = p1 - p0;
          const double den = cross(d, e);
          if (std::abs(den) <= 1e-300) continue;  // parallel
          const double s = cross(a - p0, e) / den;
          u = cross(a - p0, d) / den;
          if (!(s >= 0.0 && s <= 1.0 && u >= 0.0 && u <= 1.0)) continue;
          if (nrm.dot(p0 - a) < 0) nrm = -nrm;  // towards the side the particle came from
          if (nrm.dot(p1 - a) > -tol) continue;
        }
        p1 = a + u * e + 0.05 * hvec_[i] * nrm;
        Vec2 v = state_.v.segment<2>(2 * i);
        const double vn = v.dot(nrm);
        if (vn < 0) v -= vn * nrm;
        state_.v.segment<2>(2 * i) = v;
        ++wall_crossings_;
      }
    }
    state_.x.segment<2>(2 * i) = p1;
  }
}

Json FluidModel::summary() const {
  const char* detection = detection_ == meshing::DomainDetection::Alpha      ? "alpha"
                          : detection_ == meshing::DomainDetection::Advected ? "advected"
                                                                             : "level_set";
  return {{"fluid_area", {{"initial", area_initial_}, {"final", area_end_}, {"left_domain", area_left_},
                          {"drift_without_left", area_initial_ > 0 ? (area_end_ + area_left_) / area_initial_ - 1.0 : 0.0}}},
          {"wall_crossings", wall_crossings_},
          {"inverted_elements_kept", inverted_kept_},
          {"particles", {{"initial", n_initial_}, {"final", n()}}},
          {"remeshing",
           {{"domain_detection", remesh_ ? detection : "none (fixed connectivity)"},
            {"area_added", remesh_area_added_},
            {"area_removed", remesh_area_removed_},
            {"kinetic_energy_change", remesh_ke_total_},
            {"potential_energy_change", remesh_pe_total_},
            {"volume_correction_energy", correction_energy_},
            {"particles_merged", merged_},
            {"edges_split", split_},
            {"particles_inserted", inserted_},
            {"particles_removed_at_walls", wall_removed_},
            {"elements_added_outside", added_outside_},
            {"elements_separated", separated_}}}};
}

void FluidModel::finalize_step() {
  step_open_ = false;
  inverted_kept_ += inverted_in_step_;
  inverted_in_step_ = 0;
  if (energy_probes_) account_energy();
  const Vec x_start = state_.x;
  if (scheme_ == "monolithic_pspg") {
    integrator_->end_step(x_, state_);
    set_wall_motion(t_new_, state_.v, state_.a);
    set_ghost_rates(state_.v, state_.a);
  } else {
    state_.a = (v_new_ - state_.v) / dt_;
    state_.v = v_new_;
    state_.x = x_;
  }
  keep_inside_walls(x_start);
  area_end_ = mesh_area();
  p_scale_ = std::max(p_scale_, p_.cwiseAbs().maxCoeff());
}

void FluidModel::write_output(double t) {
  const auto t0 = Clock::now();
  if (!series_) series_ = std::make_unique<PvdSeries>(ctx_.out_dir, name_);
  const Index np = n();
  TriMesh mesh;
  mesh.order = 1;
  mesh.nodes.resize(np);
  for (Index i = 0; i < np; ++i) mesh.nodes[i] = state_.x.segment<2>(2 * i);
  mesh.conn = conn_.size() == 3 * tri_.size() ? conn_ : std::vector<Index>();
  if (mesh.conn.empty())
    for (const auto& tr : tri_) mesh.conn.insert(mesh.conn.end(), tr.begin(), tr.end());
  VtuData d;
  d.mesh = &mesh;
  Field vel{"velocity", 2, {}}, pres{"pressure", 1, {}}, fs{"free_surface", 1, {}}, kd{"kind", 1, {}},
      id{"particle_id", 1, {}};
  for (Index i = 0; i < np; ++i) {
    vel.values.push_back(state_.v[2 * i]);
    vel.values.push_back(state_.v[2 * i + 1]);
    pres.values.push_back(p_[i]);
    fs.values.push_back(free_.empty() ? 0.0 : free_[i]);
    kd.values.push_back(static_cast<double>(kind_[i]));
    id.values.push_back(i);
  }
  d.point_fields = {vel, pres, fs, kd, id};
  series_->write(t, d);
  if (remesh_ && !walls_.empty()) {
    if (!wall_series_) wall_series_ = std::make_unique<PvdSeries>(ctx_.out_dir, name_ + "_walls");
    VtpData w;
    Field wp{"pressure", 1, {}};
    for (const auto& wall : walls_) {
      std::vector<Index> line;
      for (Index j : wall.particles) {
        line.push_back(static_cast<Index>(w.points.size()));
        w.points.push_back(state_.x.segment<2>(2 * j));
        wp.values.push_back(p_[j]);
      }
      w.lines.push_back(line);
    }
    w.point_fields = {wp};
    wall_series_->write(t, w);
  }
  times_.output += seconds_since(t0);
}

// ------------------------------------------------------------------------------------------ probes

std::unique_ptr<Probe> FluidModel::make_probe(Params p) {
  const std::string t = p.choice("type", {"front", "column_height", "pressure", "elevation", "fluid_area",
                                          "kinetic_energy", "potential_energy", "gravity_work",
                                          "viscous_dissipation", "volume_correction_energy", "total_energy",
                                          "boundary_work", "max_speed"});
  // The work of gravity and the dissipation are summed over the run only when a probe asks for them (an
  // extra element loop per step).
  if (t == "gravity_work" || t == "viscous_dissipation" || t == "total_energy" || t == "boundary_work")
    energy_probes_ = true;
  return std::make_unique<FluidProbe>(*this, p.string("name"), t, p);
}

FluidProbe::FluidProbe(const FluidModel& m, std::string name, std::string type, Params p)
    : m_(m), name_(std::move(name)), type_(std::move(type)) {
  const double h = m.spacing();
  // Where there is something to measure: the particles' extent (fluid and walls) at the start, plus h. A
  // probe outside it is a typing error (x of another case, a flipped sign) that would write nan or 0 for ever.
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (Index i = 0; i < m.n(); ++i) {
    lo = lo.cwiseMin(m.pos(i));
    hi = hi.cwiseMax(m.pos(i));
  }
  lo -= Vec2::Constant(h);
  hi += Vec2::Constant(h);
  // A band narrower than a quarter of the spacing sees no particle (a nan for ever).
  auto read_band = [&] {
    band_ = p.positive("band");
    if (band_ < 0.25 * h) p.fail("band", "narrower than a quarter of the particle spacing: it would see no particle");
  };
  auto inside = [&](const std::string& key, double v, int axis) {
    if (!(v >= lo[axis] && v <= hi[axis]))
      p.fail(key, "lies outside the fluid and its walls (" + std::string(axis ? "y" : "x") + " from " +
                      std::to_string(lo[axis] + h) + " to " + std::to_string(hi[axis] - h) + ")");
  };
  if (type_ == "front") {
    // largest x of fluid within a band above the floor
    p.validate({{"name", nullptr}, {"type", type_}, {"body", nullptr}, {"floor", 0.0}, {"band", 2.0 * h}});
    coord_ = p.number("floor");
    inside("floor", coord_, 1);
    read_band();
  } else if (type_ == "column_height") {
    // largest y of fluid within a band next to the left wall
    p.validate({{"name", nullptr}, {"type", type_}, {"body", nullptr}, {"wall", 0.0}, {"band", 2.0 * h}});
    coord_ = p.number("wall");
    inside("wall", coord_, 0);
    read_band();
  } else if (type_ == "elevation") {
    // "mesh": the highest point of the meshed fluid on the vertical line x (free-surface edges
    // interpolated); "particles": the highest fluid particle within `band` of x (biased upwards by the
    // particle noise of the surface, kept for comparison).
    p.validate({{"name", nullptr}, {"type", type_}, {"body", nullptr}, {"x", nullptr}, {"method", "mesh"},
                {"band", 1.5 * h}});
    coord_ = p.number("x");
    inside("x", coord_, 0);
    read_band();
    mesh_method_ = p.choice("method", {"mesh", "particles"}) == "mesh";
  } else if (type_ == "pressure") {
    p.validate({{"name", nullptr}, {"type", type_}, {"body", nullptr}, {"from", nullptr}, {"to", nullptr},
                {"tolerance", 0.5 * h}});
    a_ = p.vec2("from");
    b_ = p.vec2("to");
    for (int axis = 0; axis < 2; ++axis) {
      inside("from", a_[axis], axis);
      inside("to", b_[axis], axis);
    }
    band_ = p.positive("tolerance");
  } else {
    p.validate({{"name", nullptr}, {"type", type_}, {"body", nullptr}});
  }
}

std::vector<double> FluidProbe::sample() const {
  const Index n = m_.n();
  if (type_ == "fluid_area") return {m_.area_end()};
  if (type_ == "kinetic_energy") return {m_.kinetic_energy()};
  if (type_ == "potential_energy") return {m_.potential_energy()};
  if (type_ == "gravity_work") return {m_.gravity_work()};
  if (type_ == "viscous_dissipation") return {m_.viscous_dissipation()};
  if (type_ == "volume_correction_energy") return {m_.correction_energy()};
  if (type_ == "total_energy") return {m_.total_energy()};
  if (type_ == "boundary_work") return {m_.boundary_work()};
  if (type_ == "max_speed") {
    double v = 0;
    for (Index i = 0; i < n; ++i)
      if (m_.is_fluid(i)) v = std::max(v, m_.vel(i).norm());
    return {v};
  }
  if (type_ == "pressure") {
    // mean pressure of the particles on the sensor segment (any kind)
    const Vec2 d = b_ - a_;
    double s = 0;
    int count = 0;
    for (Index i = 0; i < n; ++i) {
      const Vec2 q = m_.pos(i);
      const double t = d.squaredNorm() > 0 ? std::clamp((q - a_).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      if ((q - (a_ + t * d)).norm() <= band_ && m_.is_connected(i)) {
        s += m_.pressure(i);
        ++count;
      }
    }
    return {count ? s / count : 0.0};
  }
  double best = -std::numeric_limits<double>::infinity();
  if (type_ == "elevation" && mesh_method_) {
    for (const auto& t : m_.triangles())
      for (int k = 0; k < 3; ++k) {
        const Vec2 a = m_.pos(t[k]), b = m_.pos(t[(k + 1) % 3]);
        const double da = a.x() - coord_, db = b.x() - coord_;
        if (da * db > 0) continue;
        best = std::max(best, da == db ? std::max(a.y(), b.y()) : a.y() + (b.y() - a.y()) * da / (da - db));
      }
    return {std::isfinite(best) ? best : std::numeric_limits<double>::quiet_NaN()};
  }
  for (Index i = 0; i < n; ++i) {
    if (!m_.is_fluid(i) || !m_.is_connected(i)) continue;
    const Vec2 q = m_.pos(i);
    if (type_ == "front" && q.y() <= coord_ + band_) best = std::max(best, q.x());
    if (type_ == "column_height" && q.x() <= coord_ + band_) best = std::max(best, q.y());
    if (type_ == "elevation" && std::abs(q.x() - coord_) <= band_) best = std::max(best, q.y());
  }
  return {std::isfinite(best) ? best : std::numeric_limits<double>::quiet_NaN()};
}

}  // namespace fluid_detail

std::unique_ptr<PhysicsModel> make_fluid_model(Params body, const CaseContext& ctx) {
  return std::make_unique<fluid_detail::FluidModel>(std::move(body), ctx);
}

}  // namespace lagfsi
