// Checkpoints of an EFG body (state_archive.hpp): the committed state of the load path (MLS parameters and
// multipliers, load factor, internal force), the material history of every integration point (the damage laws'
// kappa and damage, the smeared crack's largest tensile and compressive strains), the path-following control's
// memory (its parameters, the arc length, the first and previous tangent responses and increments that set the
// predictor's sign, the sign of generalized displacement control, its counters), the body's counters and the
// output series. The probes of an EFG body read the committed state and keep nothing of their own. Taken after
// a step; a restart reads it over the state initialize() set. The trial state of a step (x_, lambda_, hist1_) is
// the committed one at the start of the next step (predict), so the committed state is all the next step reads.
#include <lagfsi/efg/efg_model.hpp>

namespace lagfsi::efg {

void PathFollowing::serialize(StateArchive& ar) {
  ar.section("path following");
  ar.io(type_, complex_roots_, inc_, dof_, scale_, steps_);
  ar.io(dUP1_first_, dUP1_prev_, dUP1_cur_, DU_prev_);
  ar.io(sign_, sign_cur_, dl_, lambda_, dlambda_step_);
  ar.io(stats_.complex_root_iterations, stats_.steps_off_constraint, stats_.max_increment_ratio);
}

void EfgModel::serialize(StateArchive& ar) {
  ar.section("efg " + name_);
  const Index nsys = nsys_;
  const std::uint64_t npoints = gps_.size();
  ar.io(x0_, lambda0_, fint0_);
  if (ar.loading() && (x0_.size() != nsys || fint0_.size() != nsys))
    throw CheckpointError("body '" + name_ + "': another number of unknowns");
  std::uint64_t n = hist0_.size();
  ar.io(n);
  if (ar.loading()) {
    if (n != npoints) throw CheckpointError("body '" + name_ + "': another number of integration points");
    hist0_.resize(n);
  }
  for (History& h : hist0_) ar.io(h.h);
  control_.serialize(ar);
  ar.io(lambda_peak_, steps_);
  if (ar.loading()) {
    x_ = x0_;
    lambda_ = lambda0_;
    hist1_ = hist0_;
  }
  serialize_series(ar, series_, ctx_.out_dir, name_);
  serialize_series(ar, gauss_series_, ctx_.out_dir, name_ + "_gauss");
}

}  // namespace lagfsi::efg
