// Conditions on the grid of an MPM body and loads on its particles (mpm_boundaries.hpp): reading them from the
// case file, and applying them to the grid arrays in the sub-steps. Fixed components are zeroed; prescribed
// motion sets the node's velocity (value * f(t), or value * int_0^t f for an accelerogram); absorbing
// boundaries are Lysmer-Kuhlemeyer dashpots; free-field boundaries couple the body's side to a 1D soil column
// shaken by the same base motion (Zienkiewicz, Bicanic & Shen 1989).
#include "mpm_boundaries.hpp"

#include <lagfsi/case.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace lagfsi::mpm {

namespace {

const KeyTable kMpmLoadKeys(
    "/bodies/*/loads/* (mpm body, type particle_force)", "A total force split equally over the selected particles.",
    {{"type", "particle_force", "`particle_force`."},
     {"select", nullptr, "The particles, by reference position (see selection (type point) and others)."},
     {"value", nullptr, "Total force [x, y] (N), scaled by the function."},
     {"function", Json{{"type", "constant"}}, "Function of time (see time function (type constant) and others)."}});

const KeyTable kMpmFixedKeys("/bodies/*/boundary_conditions/* (mpm body, type fixed)", "Grid nodes held.",
                             {{"type", "fixed", "`fixed`."},
                              {"select", nullptr, "The grid nodes (see selection (type point) and others)."},
                              {"components", "xy", "Held components: x, y or xy."}});

const KeyTable kMpmPrescribedKeys(
    "/bodies/*/boundary_conditions/* (mpm body, type prescribed_velocity or prescribed_acceleration)",
    "Grid nodes moved with value f(t) (velocity) or its integral (acceleration); components whose value is 0 are free.",
    {{"type", nullptr, "prescribed_velocity or prescribed_acceleration."},
     {"select", nullptr, "The grid nodes (see selection (type point) and others)."},
     {"value", nullptr, "Velocity (m/s) or acceleration (m/s^2) [x, y], scaled by the function."},
     {"function", nullptr, "Function of time, e.g. an accelerogram as a table (see time function (type table))."}});

const KeyTable kMpmAbsorbingKeys(
    "/bodies/*/absorbing_boundaries/* (mpm body)",
    "Lysmer-Kuhlemeyer dashpots on grid nodes, or a free-field lateral boundary (a 1D column beside it).",
    {{"select", nullptr, "The grid nodes (see selection (type point) and others)."},
     {"normal", nullptr, "Outward normal [x, y] (free field: [1, 0] or [-1, 0])."},
     {"free_field", false, "A lateral boundary with a free-field column of the body's material."},
     {"start", 0.0, "Free field: rollers until this time (s), their reactions after (0: off)."}});

}  // namespace

// ------------------------------------------------------------------------------------------ applying

void GridBoundaries::impose_motion(Grid& grid, double t1, double dt) const {
  for (const auto& m : moving) {
    if (!(grid.mass[m.node] > 0)) continue;
    const double v1 = m.velocity(t1);
    grid.force[m.node][m.comp] += grid.mass[m.node] * (v1 - grid.velocity[m.node][m.comp]) / dt;
    grid.velocity[m.node][m.comp] = v1;
    grid.momentum[m.node][m.comp] = grid.mass[m.node] * v1;
  }
}

void GridBoundaries::add_free_field_tractions(Grid& grid, double t, const MpmMaterial& mat, double damp_stiff) const {
  const double lambda = mat.lame_lambda(), mu = mat.shear_modulus();
  for (auto& ff : free_fields) {
    const size_t m = ff.nodes.size();
    if (!ff.active(t)) continue;
    for (size_t k = 0; k < m; ++k) {
      const Index n = ff.nodes[k];
      if (!(grid.mass[n] > 0)) continue;
      // Column stress at the node: the average of its elements' (the static part at the node).
      Vec2 e = Vec2::Zero();
      int ne = 0;
      for (size_t el : {k - 1, k})
        if (el < m - 1) {
          e += ff.strain(el, damp_stiff);
          ++ne;
        }
      e /= ne;
      // e = (gamma_xy, eps_yy) with the body's stiffness-proportional damping: sigma_xx = K0 sigma_v +
      // lambda eps_yy, sigma_xy = mu gamma_xy.
      const double sxx = (ff.start > 0 ? 0.0 : k0 * ff.sv[k]) + lambda * e.y();
      const double sxy = mu * e.x();
      grid.force[n] += ff.length[k] * Vec2(sxx * ff.normal.x(), sxy * ff.normal.x()) + Vec2(ff.reaction[k], 0.0);
    }
  }
}

void GridBoundaries::add_dashpot_forces(Grid& grid, double t, double dt, const MpmMaterial& mat) {
  // A dashpot force -C (v - v_ref), C = rho L (c_p n n^T + c_s (I - n n^T)), taken at the end-of-step
  // velocity: (m I + dt C) v_new = p + dt f + dt C v_ref. Implicit in the node's own velocity, it is stable for
  // any nodal mass (an explicit dashpot on a node with little mass, at the edge of the material, is not).
  const double rho = mat.density();
  const double cp = mat.p_wave_speed(), cs = mat.s_wave_speed();
  auto apply = [&](Index n, const Vec2& normal, double length, const Vec2& v_ref) {
    if (!(grid.mass[n] > 0)) return;
    const Mat2 nn = normal * normal.transpose();
    const Mat2 C = rho * length * (cp * nn + cs * (Mat2::Identity() - nn));
    const Mat2 A = grid.mass[n] * Mat2::Identity() + dt * C;
    const Vec2 v_new = A.inverse() * (grid.momentum[n] + dt * grid.force[n] + dt * C * v_ref);
    grid.force[n] -= C * (v_new - v_ref);
  };
  for (const auto& d : dashpots) apply(d.node, d.normal, d.length, Vec2::Zero());
  for (auto& ff : free_fields)
    for (size_t k = 0; k < ff.nodes.size(); ++k) {
      const Index n = ff.nodes[k];
      if (ff.active(t)) {
        apply(n, ff.normal, ff.length[k], ff.v[k]);
      } else if (grid.mass[n] > 0) {  // a roller: its reaction holds the node's horizontal momentum
        ff.reaction[k] = -(grid.momentum[n].x() / dt + grid.force[n].x());
        grid.force[n].x() += ff.reaction[k];
      }
    }
}

void GridBoundaries::step_free_fields(double t, double dt, const MpmMaterial& mat, double damp_mass,
                                      double damp_stiff) {
  const double lambda = mat.lame_lambda(), mu = mat.shear_modulus();
  for (auto& ff : free_fields) {
    const size_t m = ff.nodes.size();
    std::vector<Vec2> f(m, Vec2::Zero());
    for (size_t k = 0; k + 1 < m; ++k) {
      // Element stress: shear mu gamma, axial (lambda + 2 mu) eps (1D constrained), with the body's
      // stiffness-proportional damping; per unit width.
      const Vec2 e = ff.strain(k, damp_stiff);
      const Vec2 s(mu * e.x(), (lambda + 2 * mu) * e.y());
      f[k] += s;
      f[k + 1] -= s;
    }
    for (size_t k = 0; k < m; ++k) {
      if (damp_mass > 0) f[k] -= damp_mass * ff.mass[k] * ff.v[k];
      ff.v[k] += dt * f[k] / ff.mass[k];
    }
    for (int c = 0; c < 2; ++c) {  // the base moves with the grid's base
      if (ff.base[c])
        ff.v[0][c] = ff.base[c]->velocity(t + dt);
      else if (ff.base_fixed[c])
        ff.v[0][c] = 0.0;
    }
    for (size_t k = 0; k < m; ++k) ff.u[k] += dt * ff.v[k];
  }
}

void add_particle_loads(const std::vector<ParticleLoad>& loads, const std::vector<Support>& support, double t,
                        std::vector<Vec2>& f) {
  for (const auto& l : loads) {
    const Vec2 F = l.fn->value(t) * l.force;
    for (Index q : l.particles) {
      const Support& sp = support[q];
      for (int k = 0; k < sp.n; ++k) f[sp.node[k]] += sp.N[k] * F;
    }
  }
}

// ------------------------------------------------------------------------------------------ reading

std::vector<ParticleLoad> read_particle_loads(Params loads, const std::vector<Vec2>& reference_positions,
                                              const std::filesystem::path& base_dir) {
  // Loads on particles: the total force split equally over the particles whose reference position the
  // selection picks, times a function of time.
  std::vector<ParticleLoad> out;
  for (size_t i = 0; i < loads.size(); ++i) {
    Params l = loads.at(i);
    l.validate(kMpmLoadKeys);
    l.choice("type", {"particle_force"});
    ParticleLoad pl;
    pl.particles = select_nodes(l.at("select"), reference_positions);
    pl.force = l.vec2("value") / static_cast<double>(pl.particles.size());
    pl.fn = make_time_function(l.at("function"), base_dir);
    out.push_back(std::move(pl));
  }
  return out;
}

void read_boundary_conditions(Params bcs, const std::vector<Vec2>& nodes, bool two_phase,
                              const std::filesystem::path& base_dir, GridBoundaries& out) {
  // Grid boundary conditions: fixed components of the selected grid nodes.
  for (size_t i = 0; i < bcs.size(); ++i) {
    Params bc = bcs.at(i);
    if (!bc.json().is_object() || !bc.has("type")) bc.fail("type", "required key is missing");
    const std::string type = bc.choice("type", {"fixed", "prescribed_velocity", "prescribed_acceleration"});
    if (type == "fixed") {
      bc.validate(kMpmFixedKeys);
      const std::string comps = bc.choice("components", {"x", "y", "xy"});
      for (Index n : select_nodes(bc.at("select"), nodes)) {
        if (comps != "y") out.fixed.push_back({n, 0});
        if (comps != "x") out.fixed.push_back({n, 1});
      }
      continue;
    }
    // The selected nodes move with value * f(t) (velocity) or value * int f (acceleration); both components
    // whose value is non-zero are prescribed, and "fixed" other components stay fixed.
    bc.validate(kMpmPrescribedKeys);
    if (two_phase) bc.fail("type", "prescribed motion of two-phase bodies is not available in this version");
    const Vec2 value = bc.vec2("value");
    std::shared_ptr<TimeFunction> fn = make_time_function(bc.at("function"), base_dir);
    for (Index n : select_nodes(bc.at("select"), nodes))
      for (int c = 0; c < 2; ++c)
        if (value[c] != 0.0) out.moving.push_back({n, c, value[c], fn, type == "prescribed_acceleration"});
  }
}

namespace {

/// A free-field column beside the vertical line of grid nodes `sel` (outward normal nrm).
FreeField read_free_field(Params a, const std::vector<Index>& sel, const Vec2& nrm, const std::vector<Vec2>& nodes,
                          const BoundaryBody& body, const GridBoundaries& bounds) {
  const double h = body.grid.h;
  const Particles& P = body.particles;
  const double rho = body.density;
  if (std::abs(nrm.y()) > 1e-12)
    a.fail("normal", "a free-field boundary is lateral: its outward normal is [1, 0] or [-1, 0]");
  FreeField ff;
  ff.normal = nrm;
  ff.start = a.non_negative("start");
  std::vector<Index> col(sel.begin(), sel.end());
  std::sort(col.begin(), col.end(), [&](Index p, Index q) { return nodes[p].y() < nodes[q].y(); });
  for (size_t k = 1; k < col.size(); ++k)
    if (std::abs(nodes[col[k]].x() - nodes[col[0]].x()) > 1e-6 * h ||
        std::abs(nodes[col[k]].y() - nodes[col[k - 1]].y() - h) > 1e-6 * h)
      a.fail("select", "a free-field boundary is one vertical line of consecutive grid nodes");
  // The column's soil: up to the top of the particles next to the boundary (their domains' top).
  const double xb = nodes[col[0]].x();
  double top = -std::numeric_limits<double>::infinity();
  for (size_t q = 0; q < P.size(); ++q)
    if (std::abs(P.x[q].x() - xb) < h) top = std::max(top, P.x[q].y() + 0.5 * h / body.particles_per_cell);
  if (!(top > nodes[col[0]].y() + 0.5 * h)) a.fail("select", "no material next to the free-field boundary");
  const double gy = body.gravity_y;
  for (size_t k = 0; k < col.size(); ++k) {
    const double y = nodes[col[k]].y();
    if (y > top + 1e-9 * h) break;
    ff.nodes.push_back(col[k]);
    ff.sv.push_back(rho * gy * (top - y));
    if (k + 1 < col.size() && nodes[col[k + 1]].y() <= top + 1e-9 * h)
      ff.le.push_back(h);
    else if (top - y > 1e-9 * h) {  // a partial last element up to the top
      ff.le.push_back(top - y);
      ff.nodes.push_back(col[k + 1 < col.size() ? k + 1 : k]);
      ff.sv.push_back(0.0);
      if (k + 1 >= col.size()) a.fail("select", "the free-field boundary must reach the top of the material");
      break;
    }
  }
  const size_t m = ff.nodes.size();
  if (m < 2) a.fail("select", "a free-field column needs at least two nodes in the material");
  ff.mass.assign(m, 0.0);
  ff.length.assign(m, 0.0);
  for (size_t k = 0; k + 1 < m; ++k) {
    ff.mass[k] += 0.5 * rho * ff.le[k];
    ff.mass[k + 1] += 0.5 * rho * ff.le[k];
    ff.length[k] += 0.5 * ff.le[k];
    ff.length[k + 1] += 0.5 * ff.le[k];
  }
  ff.u.assign(m, Vec2::Zero());
  ff.v.assign(m, Vec2::Zero());
  ff.reaction.assign(m, 0.0);
  for (const auto& mv : bounds.moving)
    if (mv.node == ff.nodes[0]) ff.base[mv.comp] = &mv;
  for (const auto& [node, comp] : bounds.fixed)
    if (node == ff.nodes[0]) ff.base_fixed[comp] = true;
  for (const auto& mv : bounds.moving)
    for (size_t k = 1; k < m; ++k)
      if (mv.node == ff.nodes[k])
        a.fail("select", "a free-field node above the base must not have a prescribed motion");
  return ff;
}

}  // namespace

void read_absorbing_boundaries(Params ab, const std::vector<Vec2>& nodes, const BoundaryBody& body,
                               GridBoundaries& out) {
  const Grid& grid = body.grid;
  const double h = grid.h;
  for (size_t i = 0; i < ab.size(); ++i) {
    Params a = ab.at(i);
    a.validate(kMpmAbsorbingKeys);
    if (!a.boolean("free_field") && a.non_negative("start") > 0) a.fail("start", "is for free-field boundaries");
    if (body.two_phase) a.fail("select", "absorbing boundaries of two-phase bodies are not available in this version");
    Vec2 nrm = a.vec2("normal");
    if (!(nrm.norm() > 0)) a.fail("normal", "must be a non-zero vector");
    nrm.normalize();
    const auto sel = select_nodes(a.at("select"), nodes);
    if (a.boolean("free_field")) {
      out.free_fields.push_back(read_free_field(a, sel, nrm, nodes, body, out));
      continue;
    }
    const std::set<Index> in(sel.begin(), sel.end());
    const Vec2 tangent(-nrm.y(), nrm.x());
    for (Index n : sel) {
      double length = 0;
      for (double s : {-1.0, 1.0}) {
        const Vec2 q = nodes[n] + s * h * tangent;  // the neighbour along the boundary, if on the grid
        const long i = std::lround((q.x() - grid.origin.x()) / h), j = std::lround((q.y() - grid.origin.y()) / h);
        if (i < 0 || j < 0 || i > grid.nx || j > grid.ny) continue;
        if ((nodes[j * (grid.nx + 1) + i] - q).norm() < 1e-6 * h && in.count(static_cast<Index>(j * (grid.nx + 1) + i)))
          length += 0.5 * h;
      }
      if (length == 0) length = h;  // a single node: one cell's length
      out.dashpots.push_back({n, nrm, length});
    }
  }
}

}  // namespace lagfsi::mpm
