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
///    Complex roots (b^2 - 4ac < 0): the line of iterates DU + dUQ + dl dUP misses the constraint sphere. It happens
///    at sharp snap-backs where the operator does not see the softening branch (a secant operator: positive definite,
///    its dUP always points up the elastic loading path). The option `complex_roots` chooses the remedy:
///     - "real_part" (default): dl = -b/2a, the real part of the complex pair, the load change that brings the
///       iterate closest to the constraint surface (the minimum of |DU + dUQ + dl dUP|^2). The constraint is relaxed
///       for that iteration only; the next ones solve the quadratic again when it has real roots, so a step that
///       converges off the sphere is one where no equilibrium point near the iterates lies on it (it crosses the
///       snap-back in one step, as generalized displacement control does). Such steps are counted (stats()).
///       Relaxing the constraint to its closest point is the remedy for sharp snap-backs attributed to
///       Hellweg & Crisfield (1998), "A new arc-length method for handling sharp snap-backs", Comput. Struct.
///       66(5):705-709, and reviewed by Ritto-Correa & Camotim (2008), Comput. Struct. 86:1353-1368; implemented
///       here from that description, not from the papers' text;
///     - "normal_plane": the linearised constraint of Ramm's updated normal plane (Ramm 1981, "Strategies for
///       tracing the nonlinear response near limit points"; Crisfield 1991, Vol. 1, §9.3): DU.(dl dUP + dUQ) = 0,
///       dl = -(DU.dUQ)/(DU.dUP), for that iteration;
///     - "cut_back": no remedy (the behaviour before this option): SolverError, the driver halves the step
///       (Crisfield 1981), and the run stops after max_step_halvings.
///    The steps where no complex root occurs are the same, bit for bit, with every option.
/// The sign of the increment is the direction of the first step along the reference load P (negative: the path
/// starts with lambda < 0, P reversed; displacement control: the controlled component decreases); the later steps
/// follow the path from there as with a positive increment (arc length: Dl = |increment| |dUP_1^1|, the sign of the
/// first predictor that of the increment).
/// Limit points. Load control cannot pass one: beyond it the load exceeds what the body carries. The predictor
/// refuses a step whose tangent response to the load has turned against the last step's, dUP_1^{i-1} . dUP_1^i <= 0
/// (the sign of Bergan's current stiffness parameter, the sign change of GSP that generalized displacement control
/// follows: the tangent stiffness is no longer positive definite along the path), with a SolverError that names
/// the limit point and the controls that pass it.
/// The vectors given are those of the control space: nodal displacements U = f(V) ("U form", Algorithm 1) or the
/// MLS parameters V ("V form", parameter control, Algorithm 6); the model maps them. A step cut back by the
/// driver scales the step's increment (dlambda, du or Dl) by `scale`.
#include <lagfsi/state_archive.hpp>
#include <lagfsi/types.hpp>

#include <string>

namespace lagfsi::efg {

enum class ControlType { load, displacement, generalized_displacement, arc_length };
enum class ComplexRoots { real_part, normal_plane, cut_back };

/// What the arc length met on its way (zero for the other controls).
struct ArcLengthStats {
  long complex_root_iterations = 0;  ///< corrector iterations that took the remedy
  int steps_off_constraint = 0;      ///< committed steps with | |DU| / Dl - 1 | > 1e-6
  double max_increment_ratio = 0;    ///< largest |DU| / Dl of a committed step (1 on the constraint)
};

class PathFollowing {
 public:
  PathFollowing() = default;
  PathFollowing(ControlType type, double increment, Index dof, ComplexRoots complex_roots = ComplexRoots::real_part)
      : type_(type), complex_roots_(complex_roots), inc_(increment), dof_(dof) {}
  ControlType type() const { return type_; }
  /// The JSON path of the control in the case file: the prefix of the messages of its errors.
  void locate(std::string json_path) { where_ = std::move(json_path); }
  const std::string& where() const { return where_; }
  /// The load factor of the last committed step (the sum of the committed steps' increments).
  double load_factor() const { return lambda_; }
  const ArcLengthStats& stats() const { return stats_; }
  /// Load-factor increment of the first iteration of a step from the tangent response dUP.
  double predictor(const Vec& dUP, double scale);
  /// Load-factor correction of iteration j > 1; DU: the step's increment so far. Throws SolverError when the
  /// arc-length constraint has complex roots and complex_roots = cut_back (the step is then cut back).
  double corrector(const Vec& dUP, const Vec& dUQ, const Vec& DU);
  /// The step converged with increment DU.
  void commit(const Vec& DU);
  /// A SolverError "<json path>: <reason>".
  [[noreturn]] void fail(const std::string& reason) const;
  /// Checkpoints: the parameters and everything the next step reads of the earlier ones (efg_checkpoint.cpp).
  void serialize(StateArchive& ar);
  static ControlType parse(const std::string& name);
  static ComplexRoots parse_complex_roots(const std::string& name);

 private:
  double step_predictor(const Vec& dUP, double scale);
  double step_corrector(const Vec& dUP, const Vec& dUQ, const Vec& DU);

  ControlType type_ = ControlType::load;
  ComplexRoots complex_roots_ = ComplexRoots::real_part;
  double inc_ = 0.1;
  Index dof_ = -1;
  double scale_ = 1;
  int steps_ = 0;             // committed steps
  Vec dUP1_first_;            // dUP_1 of the first step (CDG)
  Vec dUP1_prev_, dUP1_cur_;  // dUP_1 of the last committed step, of this step
  Vec DU_prev_;               // increment of the last committed step (arc length)
  double sign_ = 1, sign_cur_ = 1;
  double dl_ = 0;                         // arc length (> 0)
  double lambda_ = 0, dlambda_step_ = 0;  // committed load factor; the step's increment so far
  std::string where_;
  ArcLengthStats stats_;
};

}  // namespace lagfsi::efg
