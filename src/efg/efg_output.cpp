// EFG output: the background cells (each quadrilateral as two triangles) with nodal displacement U = f(V) and the
// parameters V as a .vtu series; the integration points with damage, stress and strain as a .vtp point cloud;
// the body's summary.json entry (discretisation, shape-function cost, conditioning, load factor, energy error).
// See src/efg/include/lagfsi/efg/efg_model.hpp.
#include <lagfsi/efg/efg_model.hpp>
#include <lagfsi/stopwatch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace lagfsi::efg {

void EfgModel::write_output(double t) {
  const auto t0 = SteadyClock::now();
  if (!series_) {
    series_ = std::make_unique<PvdSeries>(ctx_.out_dir, name_);
    gauss_series_ = std::make_unique<PvdSeries>(ctx_.out_dir, name_ + "_gauss");
  }
  TriMesh tri;
  tri.order = 1;
  tri.nodes = mesh_.nodes;
  for (const auto& c : mesh_.cells) {
    tri.conn.insert(tri.conn.end(), {c[0], c[1], c[2]});
    tri.conn.insert(tri.conn.end(), {c[0], c[2], c[3]});
  }
  const Vec u = nodal_displacements();
  VtuData d;
  d.mesh = &tri;
  Field fu{"displacement", 2, std::vector<double>(u.data(), u.data() + u.size())};
  Field fv{"parameter", 2, std::vector<double>(x0_.data(), x0_.data() + ndof_)};
  Field fa{"active_fe_node", 1, {}};
  for (char a : active_) fa.values.push_back(a);
  d.point_fields = {fu, fv, fa};
  series_->write(t, d);
  VtpData g;
  Field dmg{"damage", 1, {}}, sg{"stress", 3, {}}, ep{"strain", 3, {}};
  // The laws' declared state variables (MaterialLaw::state_variables), one field each (0 where a region's law has
  // none of that name); "damage" is written above for every law.
  std::vector<Field> state;
  const auto declare = [&](const Material& m) {
    for (const std::string& name : m.state_variables())
      if (name != "damage" && std::none_of(state.begin(), state.end(), [&](const Field& f) { return f.name == name; }))
        state.push_back({name, 1, {}});
  };
  declare(*material_);
  for (const auto& m : region_materials_) declare(*m);
  for (size_t i = 0; i < gps_.size(); ++i) {
    const GaussPoint& gp = gps_[i];
    g.points.push_back(gp.x);
    Vec3 e = Vec3::Zero();
    for (Index k = 0; k < gp.n; ++k) {
      const Index j = gp.begin + k, n = gnode_[j];
      e[0] += gNx_[j] * x0_[2 * n];
      e[1] += gNy_[j] * x0_[2 * n + 1];
      e[2] += gNy_[j] * x0_[2 * n] + gNx_[j] * x0_[2 * n + 1];
    }
    const Material& mat = cell_material_[gp.cell] < 0 ? *material_ : *region_materials_[cell_material_[gp.cell]];
    History h;
    Vec3 s;
    Mat3 E;
    mat.stress(e, hist0_[i], h, s, E);
    dmg.values.push_back(mat.damage(hist0_[i]));
    const std::vector<std::string> names = mat.state_variables();
    for (Field& f : state) {
      const auto k = static_cast<size_t>(std::find(names.begin(), names.end(), f.name) - names.begin());
      f.values.push_back(k < names.size() && k < hist0_[i].h.size() ? hist0_[i].h[k] : 0.0);
    }
    for (int k = 0; k < 3; ++k) {
      sg.values.push_back(s[k]);
      ep.values.push_back(e[k]);
    }
  }
  g.point_fields = {dmg, sg, ep};
  g.point_fields.insert(g.point_fields.end(), state.begin(), state.end());
  gauss_series_->write(t, g);
  times_.output += std::chrono::duration<double>(SteadyClock::now() - t0).count();
}

std::pair<double, double> EfgModel::energy_error() const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!exact_.available()) return {nan, nan};
  // Plane-stress compliance of the exact solution's constants.
  const double E = exact_.E, nu = exact_.nu;
  Mat3 C;
  C << 1 / E, -nu / E, 0, -nu / E, 1 / E, 0, 0, 0, 2 * (1 + nu) / E;
  const Mat3 D = C.inverse();
  double err = 0, ref = 0;
  for (const auto& gp : gps_) {
    Vec3 e = Vec3::Zero();
    for (Index k = 0; k < gp.n; ++k) {
      const Index j = gp.begin + k, n = gnode_[j];
      e[0] += gNx_[j] * x0_[2 * n];
      e[1] += gNy_[j] * x0_[2 * n + 1];
      e[2] += gNy_[j] * x0_[2 * n] + gNx_[j] * x0_[2 * n + 1];
    }
    const Vec3 ee = lambda0_ * (C * exact_.stress(gp.x));
    const Vec3 de = e - ee;
    err += 0.5 * de.dot(D * de) * gp.w;
    ref += 0.5 * ee.dot(D * ee) * gp.w;
  }
  return {std::sqrt(err), ref > 0 ? std::sqrt(err / ref) : nan};
}

Json EfgModel::summary() const {
  Json s;
  s["gauss_points"] = gps_.size();
  s["dofs"] = nsys_;
  s["essential"] = essential_;
  s["active_fe_nodes"] = std::count(active_.begin(), active_.end(), 1);
  s["coupling_cells"] = std::count(coupling_cell_.begin(), coupling_cell_.end(), 1);
  s["support_mean"] = mean_support_;
  s["support_max"] = max_support_;
  s["moment_rcond_min"] = min_rcond_;
  s["shape_function_time"] = t_shape_;
  s["shape_function_time_per_point_us"] = gps_.empty() ? 0.0 : 1e6 * t_shape_ / gps_.size();
  s["load_factor"] = lambda0_;
  s["load_factor_peak"] = lambda_peak_;
  s["load_steps"] = steps_;
  if (control_.type() == ControlType::arc_length) {
    const ArcLengthStats& a = control_.stats();
    s["arc_length"] = {{"complex_root_iterations", a.complex_root_iterations},
                       {"steps_off_constraint", a.steps_off_constraint},
                       {"max_increment_ratio", a.max_increment_ratio}};
  }
  double dmax = 0;
  for (size_t i = 0; i < hist0_.size(); ++i) {
    const Material& mat =
        cell_material_[gps_[i].cell] < 0 ? *material_ : *region_materials_[cell_material_[gps_[i].cell]];
    dmax = std::max(dmax, mat.damage(hist0_[i]));
  }
  s["damage_max"] = dmax;
  if (exact_.available()) {
    const auto [a, r] = energy_error();
    s["energy_error"] = a;
    s["energy_error_relative"] = r;
  }
  return s;
}

}  // namespace lagfsi::efg
