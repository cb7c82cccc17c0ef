#pragma once
/// @file acceleration.hpp
/// Acceleration of the fixed-point iteration of a partitioned (Dirichlet–Neumann) coupling, after the
/// `Acceleration` classes of preCICE. Within a time step the coupling iterates on the interface unknowns x
/// (e.g. the interface positions):
///
///   x~_k = H(x_k)      one coupling pass (fluid with x_k prescribed, solid loaded by the fluid's tractions)
///   r_k  = x~_k - x_k  the interface residual
///
/// and an acceleration returns x_{k+1} from (x_k, x~_k) and what it kept of earlier iterations:
///
///  - "constant": x_{k+1} = x_k + w r_k (under-relaxation, 0 < w <= 1);
///  - "aitken": the same with Aitken's dynamic factor (Irons & Tuck 1969; Küttler & Wall 2008, Comput. Mech.
///    43:61): w_k = -w_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2, w_0 = the initial relaxation each step;
///  - "iqn_ils": interface quasi-Newton with an inverse Jacobian from a least-squares model (Degroote, Bathe &
///    Vierendeels 2009, Comput. Struct. 87:793): with V = [dr_i] and W = [dx~_i] the differences of successive
///    residuals and outputs (this step's, newest first, then those of up to `reuse_steps` earlier steps),
///    alpha = argmin |V alpha + r_k|, x_{k+1} = x~_k + W alpha. The least-squares problem is solved by a QR
///    decomposition built column by column (modified Gram–Schmidt); a column whose part orthogonal to the
///    ones before it is below `filter` times its own norm is dropped (the QR filter of Haelterman et al. 2016,
///    which keeps the model well conditioned when reused columns become nearly dependent). Without columns
///    (the first iteration) it relaxes with the initial relaxation;
///  - "iqn_imvj": interface quasi-Newton with a multi-vector inverse Jacobian (Lindner, Mehl, Scheufele &
///    Uekermann 2015, SIAM J. Sci. Comput. 37:S145): the previous steps' inverse Jacobian J_prev (dense,
///    n x n) corrected by this step's columns, J = J_prev + (W - J_prev V)(V^T V)^-1 V^T, and
///    x_{k+1} = x~_k - J r_k; J is kept at the end of each step. No columns of old steps, so nothing to go
///    stale when the interface's contact state changes; the first step is ILS without reuse.
///
/// Contract: begin_step() before the first update() of a time step; update(x, x~) once per coupling
/// iteration; end_step() after the step converged (iqn_ils then keeps the step's columns for reuse, iqn_imvj
/// its Jacobian).
#include <lagfsi/params.hpp>
#include <lagfsi/state_archive.hpp>
#include <lagfsi/types.hpp>

#include <memory>
#include <string>

namespace lagfsi::fsi {

class Acceleration {
 public:
  virtual ~Acceleration() = default;
  /// The case-file type string.
  virtual std::string type() const = 0;
  virtual void begin_step() {}
  /// The next iterate from the current one x and the coupling pass's output x_tilde (same size every
  /// iteration of a step; a new size is allowed at a new step, when the interface changed).
  virtual Vec update(const Vec& x, const Vec& x_tilde) = 0;
  virtual void end_step() {}
  /// Forgets everything kept from earlier iterations and steps (after a failed step: a model built on
  /// another mesh or contact state can send the next iterate far off).
  virtual void reset() {}
  /// Columns of the least-squares model in use (iqn_ils, iqn_imvj; 0 for the others), for logs and tests.
  virtual int model_columns() const { return 0; }
  /// Checkpoints: what is kept from step to step (Aitken's factor, the reused columns, the Jacobian).
  virtual void serialize(StateArchive&) {}
};

/// Builds an acceleration from its case-file object, validated against the type's defaults:
/// {"type": "constant", "relaxation": 0.5} | {"type": "aitken", "initial_relaxation": 0.5} |
/// {"type": "iqn_ils", "initial_relaxation": 0.1, "reuse_steps": 8, "filter": 1e-8} |
/// {"type": "iqn_imvj", "initial_relaxation": 0.1, "filter": 1e-8}.
std::unique_ptr<Acceleration> make_acceleration(Params p);

}  // namespace lagfsi::fsi
