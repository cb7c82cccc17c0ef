// Probes of an MPM body (src/mpm/include/lagfsi/mpm/mpm_model.hpp): a particle's displacement, velocity,
// acceleration, stress or pore pressure (the particle nearest a reference position), the body's energies, the
// run-out front, the height of the material at a vertical line, and the mean pore pressure.
#include "mpm_body.hpp"

#include <lagfsi/mpm/mpm_model.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace lagfsi::mpm {

namespace {

const KeyTable kMpmPorePressureProbeKeys("/probes/* (mpm body, type mean_pore_pressure)",
                                         "sum p V / sum V over a two-phase body (Pa, compression positive).",
                                         probe_keys({"mean_pore_pressure"}, {}));

const KeyTable kMpmFrontProbeKeys("/probes/* (mpm body, type front)", "The largest x (m) of the particles.",
                                  probe_keys({"front"}, {}));

const KeyTable kMpmHeightProbeKeys(
    "/probes/* (mpm body, type height)", "The largest y (m) of the particles near a vertical line.",
    probe_keys({"height"},
               {{"x", nullptr, "x (m) of the line, inside the grid."},
                {"band", 0.0, "Half-width (m) of the band; default: cell / particles_per_cell.", kDerived}}));

const KeyTable kMpmEnergyProbeKeys("/probes/* (mpm body, type energy)", "An energy of the body (J per m).",
                                   probe_keys({"energy"},
                                              {{"kind", "total", "kinetic, strain, total or gravity_work."}}));

const KeyTable kMpmParticleProbeKeys(
    "/probes/* (mpm body, type particle)", "A quantity of the particle nearest to a reference position.",
    probe_keys({"particle"},
               {{"at", nullptr, "Reference position [x, y] (m); a particle within a cell of it."},
                {"quantity", "displacement_y",
                 "displacement_x, displacement_y (m), velocity_x, velocity_y (m/s), acceleration_x, acceleration_y "
                 "(m/s^2), stress_xx, stress_yy, stress_xy or pore_pressure (Pa)."}}));

class MpmProbe final : public Probe {
 public:
  MpmProbe(const MpmModel& m, std::string name, std::string quantity, Index particle)
      : m_(m), name_(std::move(name)), quantity_(std::move(quantity)), p_(particle) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;
  void set_line(double x, double band) {
    x_ = x;
    band_ = band;
  }

 private:
  const MpmModel& m_;
  std::string name_, quantity_;
  Index p_;
  double x_ = 0, band_ = 0;
};

std::vector<double> MpmProbe::sample() const {
  const Particles& P = m_.particles();
  if (quantity_ == "mean_pore_pressure") {
    double pv = 0, v = 0;
    for (size_t k = 0; k < P.size(); ++k) {
      pv -= P.pore_pressure[k] * P.volume[k];
      v += P.volume[k];
    }
    return {pv / v};
  }
  if (quantity_ == "front" || quantity_ == "height") {
    double best = -std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < P.size(); ++k) {
      if (quantity_ == "front")
        best = std::max(best, P.x[k].x());
      else if (std::abs(P.x[k].x() - x_) <= band_)
        best = std::max(best, P.x[k].y());
    }
    return {std::isfinite(best) ? best : std::numeric_limits<double>::quiet_NaN()};
  }
  if (p_ < 0) {
    if (quantity_ == "kinetic") return {m_.kinetic_energy()};
    if (quantity_ == "strain") return {m_.strain_energy()};
    if (quantity_ == "gravity_work") return {m_.gravity_work()};
    return {m_.kinetic_energy() + m_.strain_energy()};
  }
  if (quantity_ == "displacement_x") return {P.x[p_].x() - P.X[p_].x()};
  if (quantity_ == "displacement_y") return {P.x[p_].y() - P.X[p_].y()};
  if (quantity_ == "velocity_x") return {P.v[p_].x()};
  if (quantity_ == "velocity_y") return {P.v[p_].y()};
  if (quantity_ == "acceleration_x") return {P.acceleration[p_].x()};
  if (quantity_ == "acceleration_y") return {P.acceleration[p_].y()};
  if (quantity_ == "stress_xx") return {P.stress[p_][0]};
  if (quantity_ == "stress_yy") return {P.stress[p_][1]};
  if (quantity_ == "pore_pressure") return {-P.pore_pressure[p_]};  // compression positive
  return {P.stress[p_][2]};
}

}  // namespace

std::unique_ptr<Probe> MpmModel::make_probe(Params p) {
  const MpmBody& B = *body_;
  const Particles& P = B.particles;
  const Grid& grid = B.grid;
  const double h = grid.h;
  const std::string t = p.choice("type", {"particle", "energy", "front", "height", "mean_pore_pressure"});
  if (t == "mean_pore_pressure") {  // sum p V / sum V over the body (compression positive)
    p.validate(kMpmPorePressureProbeKeys);
    if (!B.two_phase) p.fail("type", "body '" + B.name + "' is not two-phase");
    return std::make_unique<MpmProbe>(*this, p.string("name"), "mean_pore_pressure", -1);
  }
  if (t == "front") {  // the largest x of any particle (a run-out)
    p.validate(kMpmFrontProbeKeys);
    return std::make_unique<MpmProbe>(*this, p.string("name"), "front", -1);
  }
  if (t == "height") {  // the largest y of the particles within `band` of the vertical line x
    p.validate(kMpmHeightProbeKeys, {{"band", h / B.shape.particles_per_cell}});
    const double x = p.number("x"), x0 = grid.origin.x(), x1 = grid.origin.x() + grid.nx * h;
    if (!(x >= x0 && x <= x1)) {  // outside the grid no particle can be: nan at every step
      std::ostringstream os;
      os << "lies outside the grid (x from " << x0 << " to " << x1 << ")";
      p.fail("x", os.str());
    }
    auto probe = std::make_unique<MpmProbe>(*this, p.string("name"), "height", -1);
    probe->set_line(x, p.positive("band"));
    return probe;
  }
  if (t == "energy") {
    p.validate(kMpmEnergyProbeKeys);
    return std::make_unique<MpmProbe>(*this, p.string("name"),
                                      p.choice("kind", {"kinetic", "strain", "total", "gravity_work"}), -1);
  }
  // The particle nearest to a reference position.
  p.validate(kMpmParticleProbeKeys);
  const std::string q =
      p.choice("quantity", {"displacement_x", "displacement_y", "velocity_x", "velocity_y", "stress_xx", "stress_yy",
                            "stress_xy", "pore_pressure", "acceleration_x", "acceleration_y"});
  const Vec2 at = p.vec2("at");
  Index best = 0;
  for (size_t k = 1; k < P.size(); ++k)
    if ((P.X[k] - at).squaredNorm() < (P.X[best] - at).squaredNorm()) best = static_cast<Index>(k);
  if ((P.X[best] - at).norm() > h) p.fail("at", "no particle within a cell of the point");
  return std::make_unique<MpmProbe>(*this, p.string("name"), q, best);
}

}  // namespace lagfsi::mpm
