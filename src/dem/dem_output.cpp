// ParaView output of a DEM body (src/dem/dem_output.hpp).
#include "dem_output.hpp"

#include <cmath>

namespace lagfsi::dem {

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
