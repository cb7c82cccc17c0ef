// ParaView output of a DEM body (src/dem/dem_output.hpp).
#include "dem_output.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace lagfsi::dem {

CraterProfile crater_profile(const DemBody& b, const CraterSettings& s) {
  CraterProfile c;
  const size_t n = b.size();
  double xmin = 1e300, xmax = -1e300;
  for (size_t p = 0; p < n; ++p) {
    xmin = std::min(xmin, b.state.x[3 * p]);
    xmax = std::max(xmax, b.state.x[3 * p]);
  }
  const double h = s.bin > 0 ? s.bin : 4 * b.r_max;
  const int nb = std::max(1, static_cast<int>(std::ceil((xmax - xmin) / h)));
  std::vector<std::vector<std::pair<double, double>>> bins(nb);  // (bottom, top) of each disc
  for (size_t p = 0; p < n; ++p) {
    const int k = std::clamp(static_cast<int>((b.state.x[3 * p] - xmin) / h), 0, nb - 1);
    const double y = b.state.x[3 * p + 1], r = b.discs.radius[p];
    bins[k].push_back({y - r, y + r});
  }
  for (int k = 0; k < nb; ++k) {
    auto& v = bins[k];
    std::sort(v.begin(), v.end());
    double top = v.empty() ? 0.0 : v[0].second;
    for (size_t q = 1; q < v.size(); ++q) {
      if (v[q].first > top + 2 * b.r_max) break;  // a gap of a diameter: airborne from here up
      top = std::max(top, v[q].second);
    }
    c.x.push_back(xmin + (k + 0.5) * h);
    c.height.push_back(top);
  }
  auto height_at = [&](double x) {
    if (c.x.empty()) return 0.0;
    if (x <= c.x.front()) return c.height.front();
    for (size_t i = 1; i < c.x.size(); ++i)
      if (x <= c.x[i])
        return c.height[i - 1] + (c.height[i] - c.height[i - 1]) * (x - c.x[i - 1]) / (c.x[i] - c.x[i - 1]);
    return c.height.back();
  };
  for (double o : s.offsets) c.depth += (s.surface - height_at(s.centre + o)) / s.offsets.size();
  // the crossings of the initial ground level left and right of the centre
  c.left = c.right = s.centre;
  for (size_t i = 0; i + 1 < c.x.size(); ++i) {
    const double a = c.height[i] - s.surface, bb = c.height[i + 1] - s.surface;
    if ((a < 0) != (bb < 0)) {
      const double xc = c.x[i] + (c.x[i + 1] - c.x[i]) * a / (a - bb);
      if (xc <= s.centre && (c.left == s.centre || xc > c.left)) c.left = xc;
      if (xc >= s.centre && (c.right == s.centre || xc < c.right)) c.right = xc;
    }
  }
  c.diameter = c.right - c.left;
  return c;
}

void DemWriter::write(double t, const DemBody& b) {
  if (!discs_) discs_ = std::make_unique<PvdSeries>(out_dir_, b.name);
  const size_t n = b.size();
  VtpData d;
  d.points.resize(n);
  Field r{"radius", 1, {}}, v{"velocity", 2, {}}, w{"angular_velocity", 1, {}}, mom{"momentum", 1, {}},
      mark{"mark", 1, {}}, id{"id", 1, {}}, group{"group", 1, {}};
  r.values.resize(n);
  v.values.resize(2 * n);
  w.values.resize(n);
  mom.values.resize(n);
  mark.values.resize(n);
  id.values.resize(n);
  group.values.resize(n);
  for (size_t p = 0; p < n; ++p) {
    d.points[p] = b.position(static_cast<Index>(p));
    r.values[p] = b.discs.radius[p];
    v.values[2 * p] = b.state.v[3 * p];
    v.values[2 * p + 1] = b.state.v[3 * p + 1];
    w.values[p] = b.state.v[3 * p + 2];
    mom.values[p] = b.discs.mass[p] * std::hypot(b.state.v[3 * p], b.state.v[3 * p + 1]);
    mark.values[p] = b.discs.mark[p];
    id.values[p] = b.discs.id[p];
    group.values[p] = b.discs.group[p];
  }
  d.point_fields = {r, v, w, mom, mark, id, group};
  discs_->write(t, d);
  if (csv_) {
    const auto path = out_dir_ / (b.name + "_discs.csv");
    const auto tmp = path.string() + ".tmp";
    {
      std::ofstream o(tmp);
      if (!o) throw std::runtime_error("cannot write " + tmp);
      o << "# " << b.name << " discs at t = " << t << "\nid,x,y,r,vx,vy,omega,mark\n" << std::setprecision(10);
      for (size_t p = 0; p < n; ++p)
        o << b.discs.id[p] << "," << d.points[p].x() << "," << d.points[p].y() << "," << b.discs.radius[p] << ","
          << b.state.v[3 * p] << "," << b.state.v[3 * p + 1] << "," << b.state.v[3 * p + 2] << ","
          << int(b.discs.mark[p]) << "\n";
    }
    std::filesystem::rename(tmp, path);
  }
  if (b.crater.enabled) {
    const CraterSettings& crater = b.crater;
    const CraterProfile c = crater_profile(b, crater);
    const auto path = out_dir_ / "crater.csv";
    const auto tmp = path.string() + ".tmp";
    {
      std::ofstream o(tmp);
      if (!o) throw std::runtime_error("cannot write " + tmp);
      o << std::setprecision(8) << "# crater of body " << b.name << " at t = " << t << ": ground level "
        << crater.surface << " m, centre x = " << crater.centre << " m\n# depth = " << c.depth << " m (mean at offsets";
      for (double off : crater.offsets) o << " " << off;
      o << " m), diameter = " << c.diameter << " m (ground-level crossings " << c.left << " .. " << c.right
        << " m)\nx,surface,depth\n";
      for (size_t i = 0; i < c.x.size(); ++i)
        o << c.x[i] << "," << c.height[i] << "," << crater.surface - c.height[i] << "\n";
    }
    std::filesystem::rename(tmp, path);
  }
  if (b.walls.empty()) return;
  if (!walls_) walls_ = std::make_unique<PvdSeries>(out_dir_, b.name + "_walls");
  VtpData wd;
  Field wid{"wall", 1, {}};
  for (size_t k = 0; k < b.walls.size(); ++k) {
    const Wall& wall = b.walls[k];
    std::vector<Index> line;
    for (const Vec2& q : wall.points) {
      line.push_back(static_cast<Index>(wd.points.size()));
      wd.points.push_back(q + wall.offset);
    }
    wd.lines.push_back(line);
    wid.values.push_back(static_cast<double>(k));
  }
  wd.cell_fields = {wid};
  walls_->write(t, wd);
}

}  // namespace lagfsi::dem
