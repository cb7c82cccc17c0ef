// The lifecycle of an MPM body (src/mpm/include/lagfsi/mpm/mpm_model.hpp): the step is advanced by the body's scheme,
// chosen when it was read (mpm_input.cpp); output in mpm_output.cpp, probes in mpm_probes.cpp.
#include "mpm_body.hpp"
#include "mpm_output.hpp"
#include "mpm_scheme.hpp"

#include <lagfsi/mpm/mpm_model.hpp>
#include <lagfsi/stopwatch.hpp>

namespace lagfsi {

namespace mpm {

namespace {}  // namespace

MpmModel::~MpmModel() = default;

std::string MpmModel::name() const { return body_->name; }
Index MpmModel::num_nodes() const { return static_cast<Index>(body_->particles.size()); }
Index MpmModel::num_elements() const { return static_cast<Index>(body_->grid.nx * body_->grid.ny); }
const Particles& MpmModel::particles() const { return body_->particles; }
const Grid& MpmModel::grid() const { return body_->grid; }
bool MpmModel::two_phase() const { return body_->two_phase; }
double MpmModel::gravity_work() const { return body_->gravity_work; }

double MpmModel::kinetic_energy() const {
  const Particles& P = body_->particles;
  double e = 0;
  for (size_t p = 0; p < P.size(); ++p) e += 0.5 * P.mass[p] * P.v[p].squaredNorm();
  return e;
}

double MpmModel::strain_energy() const {
  const Particles& P = body_->particles;
  double e = 0;
  for (size_t p = 0; p < P.size(); ++p) {
    const auto& s = P.stress[p];
    const auto& d = P.strain[p];
    e += 0.5 * P.volume[p] * (s[0] * d[0] + s[1] * d[1] + 2.0 * s[2] * d[2]);
  }
  return e;
}

void MpmModel::initialize() { body_->t = 0; }

void MpmModel::save_step_start() {
  if (!snapshot_) snapshot_ = std::make_unique<MpmStepSnapshot>();
  snapshot_->save(*body_);
}

void MpmModel::restore_step_start() { snapshot_->restore(*body_); }

int MpmModel::advance(double t_new, double dt) {
  const int n = scheme_->advance(*body_, t_new, dt);
  substeps_ += n;
  return n;
}

void MpmModel::write_output(double t) {
  const auto t0 = SteadyClock::now();
  writer_->write(t, *body_);
  times_.output += seconds_since(t0);
}

}  // namespace mpm

std::unique_ptr<PhysicsModel> make_mpm_model(Params body, const CaseContext& ctx) {
  return std::make_unique<mpm::MpmModel>(std::move(body), ctx);
}

}  // namespace lagfsi
