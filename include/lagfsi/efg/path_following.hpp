#pragma once
/// @file path_following.hpp
/// Incremental-iterative path following of Yang & Kuo (1994) as the INSANE EFG thesis uses it (§4.2, Algorithms 1
/// and 6, Tables 4.1-4.2; digest shared/spec/003_efg.md §2.8). Iteration j of step i solves
///   K dU_j = dlambda_j P + Q_{j-1},  dU_j = dlambda_j dUP_j + dUQ_j,  K dUP = P, K dUQ = Q,
/// and the method fixes dlambda:
///  - load control:   dlambda_1 = given increment; dlambda_j = 0;
///  - displacement control (CDD) of dof k: dlambda_1 = du_k / dUP_1,k; dlambda_j = -dUQ_j,k / dUP_j,k;
///  - generalized displacement control (CDG): dlambda_1 = s_i dlambda_1^1 sqrt|GSP|,
///    GSP = (dUP_1^1 . dUP_1^1)/(dUP_1^{i-1} . dUP_1^i), s_i = s_{i-1} sign(GSP) (the direction flips where the
///    tangent response reverses, at a limit point); dlambda_j = -(dUP_1^{i-1} . dUQ_j)/(dUP_1^{i-1} . dUP_j);
///  - cylindrical arc length (Crisfield): |DU|^2 = Dl^2 with Dl = dlambda_1^1 |dUP_1^1| from the first step;
///    predictor +-Dl/|dUP| with the sign of DU_{i-1} . dUP; corrector the root of a dl^2 + b dl + c = 0,
///    a = dUP.dUP, b = 2 dUP.(DU + dUQ), c = |DU + dUQ|^2 - Dl^2, closest to the step direction.
/// The vectors given are those of the control space: nodal displacements U = f(V) ("U form", Algorithm 1) or the
/// MLS parameters V ("V form", parameter control, Algorithm 6); the model maps them. A step cut back by the
/// driver scales the step's increment (dlambda, du or Dl) by `scale`.
#include <lagfsi/types.hpp>

#include <string>

namespace lagfsi::efg {

enum class ControlType { load, displacement, generalized_displacement, arc_length };

class PathFollowing {
 public:
  PathFollowing() = default;
  PathFollowing(ControlType type, double increment, Index dof) : type_(type), inc_(increment), dof_(dof) {}
  ControlType type() const { return type_; }
  /// Load-factor increment of the first iteration of a step from the tangent response dUP.
  double predictor(const Vec& dUP, double scale);
  /// Load-factor correction of iteration j > 1; DU: the step's increment so far. Throws SolverError when the
  /// constraint has no solution (the step is then cut back).
  double corrector(const Vec& dUP, const Vec& dUQ, const Vec& DU);
  /// The step converged with increment DU.
  void commit(const Vec& DU);
  static ControlType parse(const std::string& name);

 private:
  ControlType type_ = ControlType::load;
  double inc_ = 0.1;
  Index dof_ = -1;
  double scale_ = 1;
  int steps_ = 0;              // committed steps
  Vec dUP1_first_;             // dUP_1 of the first step (CDG)
  Vec dUP1_prev_, dUP1_cur_;   // dUP_1 of the last committed step, of this step
  Vec DU_prev_;                // increment of the last committed step (arc length)
  double sign_ = 1, sign_cur_ = 1;
  double dl_ = 0;              // arc length
};

}  // namespace lagfsi::efg
