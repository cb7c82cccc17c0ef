// Output of an MPM body (mpm_output.hpp): ParaView series of the particles and of the grid, and the particles'
// CSV (written to a temporary file, then renamed, so that a reader never sees half of it).
#include "mpm_output.hpp"

#include <lagfsi/output_file.hpp>

#include <iomanip>
#include <sstream>

namespace lagfsi::mpm {

void MpmWriter::write(double t, const MpmBody& b) {
  const Particles& P = b.particles;
  const Grid& grid = b.grid;
  const std::string& name = b.name;
  if (!series_) series_ = std::make_unique<PvdSeries>(out_dir_, name);
  VtpData d;
  d.points = P.x;
  Field u{"displacement", 2, {}}, v{"velocity", 2, {}}, s{"stress", 4, {}}, vol{"volume", 1, {}},
      pl{"plastic_multiplier", 1, {}}, pw{"pore_pressure", 1, {}};
  for (size_t p = 0; p < P.size(); ++p) {
    for (int c = 0; c < 2; ++c) {
      u.values.push_back(P.x[p][c] - P.X[p][c]);
      v.values.push_back(P.v[p][c]);
    }
    for (double x : P.stress[p]) s.values.push_back(x);
    vol.values.push_back(P.volume[p]);
    pl.values.push_back(P.plastic_multiplier[p]);
    pw.values.push_back(-P.pore_pressure[p]);
  }
  d.point_fields = {u, v, s, vol, pl};
  if (b.two_phase) d.point_fields.push_back(pw);
  series_->write(t, d);
  if (grid_output_) {
    // The grid of the last sub-step: nodes with mass, their mass, velocity and the force of that sub-step
    // (internal, gravity, loads, boundaries), and whether a component is fixed or prescribed.
    if (!grid_series_) grid_series_ = std::make_unique<PvdSeries>(out_dir_, name + "_grid");
    std::vector<int> held(grid.mass.size(), 0);
    for (const auto& [node, comp] : b.boundaries.fixed) held[node] |= 1 << comp;
    for (const auto& m : b.boundaries.moving) held[m.node] |= 4 << m.comp;
    VtpData g;
    Field mass{"mass", 1, {}}, vel{"velocity", 2, {}}, force{"force", 2, {}}, bc{"boundary", 1, {}};
    for (int j = 0; j <= grid.ny; ++j)
      for (int i = 0; i <= grid.nx; ++i) {
        const size_t n = static_cast<size_t>(j) * (grid.nx + 1) + i;
        if (!(grid.mass[n] > 0)) continue;
        g.points.push_back(grid.node_position(i, j));
        mass.values.push_back(grid.mass[n]);
        for (int c = 0; c < 2; ++c) {
          vel.values.push_back(grid.velocity[n][c]);
          force.values.push_back(grid.force[n][c]);
        }
        bc.values.push_back(held[n]);  // bits: 1 x fixed, 2 y fixed, 4 x prescribed, 8 y prescribed
      }
    g.point_fields = {mass, vel, force, bc};
    grid_series_->write(t, g);
  }
  if (particles_csv_) {
    std::ostringstream o;  // written through write_file_atomic: every write checked
    {
      o << "# " << name << " particles at t = " << t << "\nX,Y,x,y,vx,vy,sxx,syy,sxy,szz,volume,pore_pressure\n"
        << std::setprecision(12);
      for (size_t p = 0; p < P.size(); ++p) {
        const auto& sg = P.stress[p];
        o << P.X[p].x() << "," << P.X[p].y() << "," << P.x[p].x() << "," << P.x[p].y() << "," << P.v[p].x() << ","
          << P.v[p].y() << "," << sg[0] << "," << sg[1] << "," << sg[2] << "," << sg[3] << "," << P.volume[p] << ","
          << -P.pore_pressure[p] << "\n";
      }
    }
    write_file_atomic(out_dir_ / (name + "_particles.csv"), o.str());
  }
}

}  // namespace lagfsi::mpm
