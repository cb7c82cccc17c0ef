#include <lagfsi/error.hpp>
#include <lagfsi/fsi/acceleration.hpp>

#include <cmath>
#include <deque>
#include <vector>

namespace lagfsi::fsi {

namespace {

class ConstantRelaxation final : public Acceleration {
 public:
  explicit ConstantRelaxation(double w) : w_(w) {}
  std::string type() const override { return "constant"; }
  Vec update(const Vec& x, const Vec& x_tilde) override { return x + w_ * (x_tilde - x); }

 private:
  double w_;
};

class Aitken final : public Acceleration {
 public:
  explicit Aitken(double w0) : w0_(w0) {}
  std::string type() const override { return "aitken"; }
  void begin_step() override { r_prev_.resize(0); }
  Vec update(const Vec& x, const Vec& x_tilde) override {
    const Vec r = x_tilde - x;
    if (r_prev_.size() != r.size()) {
      w_ = w0_;
    } else {
      const Vec dr = r - r_prev_;
      const double d2 = dr.squaredNorm();
      if (d2 > 0) w_ = -w_ * r_prev_.dot(dr) / d2;
    }
    r_prev_ = r;
    return x + w_ * r;
  }
  void serialize(StateArchive& ar) override { ar.io(w_, r_prev_); }

 private:
  double w0_, w_ = 0;
  Vec r_prev_;
};

/// Filtered least squares on difference columns: QR of V by modified Gram-Schmidt, column by column; a
/// column whose part orthogonal to the ones before it is below `filter` times its own norm is dropped.
/// Solves min |V alpha + r| over the kept columns.
struct FilteredLeastSquares {
  std::vector<Vec> Q;                  // orthonormal columns
  std::vector<std::vector<double>> R;  // R[j] = column j of R (entries 0..j)
  std::vector<size_t> kept;            // indices of the kept columns of V
  std::vector<double> alpha;           // coefficients of the kept columns

  FilteredLeastSquares(const std::vector<const Vec*>& V, const Vec& r, double filter) {
    for (size_t c = 0; c < V.size(); ++c) {
      Vec q = *V[c];
      const double norm0 = q.norm();
      if (!(norm0 > 0)) continue;
      std::vector<double> rc(Q.size() + 1, 0.0);
      for (size_t j = 0; j < Q.size(); ++j) {
        rc[j] = Q[j].dot(q);
        q -= rc[j] * Q[j];
      }
      const double nq = q.norm();
      if (nq < filter * norm0) continue;
      rc[Q.size()] = nq;
      Q.push_back(q / nq);
      R.push_back(std::move(rc));
      kept.push_back(c);
    }
    alpha = back_substitute([&](size_t j) { return -Q[j].dot(r); });
  }
  /// y = R^-1 b for b_j given by a function.
  template <class B>
  std::vector<double> back_substitute(B b) const {
    const size_t m = kept.size();
    std::vector<double> y(m, 0.0);
    for (size_t j = m; j-- > 0;) {
      double s = b(j);
      for (size_t l = j + 1; l < m; ++l) s -= R[l][j] * y[l];
      y[j] = s / R[j][j];
    }
    return y;
  }
};

/// This step's difference columns, newest first: dr_i = r_i - r_{i-1}, dx_i = x~_i - x~_{i-1}.
void step_differences(const std::vector<Vec>& r, const std::vector<Vec>& xt, std::vector<Vec>& dr,
                      std::vector<Vec>& dx) {
  dr.clear();
  dx.clear();
  for (size_t i = r.size(); i-- > 1;) {
    dr.push_back(r[i] - r[i - 1]);
    dx.push_back(xt[i] - xt[i - 1]);
  }
}

class IqnIls final : public Acceleration {
 public:
  IqnIls(double w0, int reuse, double filter) : w0_(w0), reuse_(reuse), filter_(filter) {}
  std::string type() const override { return "iqn_ils"; }
  int model_columns() const override { return columns_; }
  void serialize(StateArchive& ar) override {
    ar.io(r_, xt_, columns_);
    std::uint64_t n = old_.size();
    ar.io(n);
    if (ar.loading()) old_.resize(n);
    for (Step& s : old_) ar.io(s.dr, s.dx);
  }

  void begin_step() override {
    r_.clear();
    xt_.clear();
  }

  void end_step() override {
    if (reuse_ <= 0 || r_.size() < 2) return;
    Step s;
    step_differences(r_, xt_, s.dr, s.dx);
    old_.push_front(std::move(s));
    while (static_cast<int>(old_.size()) > reuse_) old_.pop_back();
  }

  void reset() override {
    old_.clear();
    r_.clear();
    xt_.clear();
    columns_ = 0;
  }

  Vec update(const Vec& x, const Vec& x_tilde) override {
    const Vec r = x_tilde - x;
    if (!r_.empty() && r_.back().size() != r.size())
      throw SolverError("iqn_ils: the interface changed size within a step");
    if (!old_.empty() && old_.front().dr.front().size() != r.size()) old_.clear();  // new interface: old model void
    r_.push_back(r);
    xt_.push_back(x_tilde);
    // Columns, newest first: this step's differences, then the reused steps' ones.
    std::vector<const Vec*> V, W;
    std::vector<Vec> dr_now, dx_now;
    step_differences(r_, xt_, dr_now, dx_now);
    for (size_t i = 0; i < dr_now.size(); ++i) {
      V.push_back(&dr_now[i]);
      W.push_back(&dx_now[i]);
    }
    for (const Step& s : old_)
      for (size_t i = 0; i < s.dr.size(); ++i) {
        V.push_back(&s.dr[i]);
        W.push_back(&s.dx[i]);
      }
    const FilteredLeastSquares ls(V, r, filter_);
    columns_ = static_cast<int>(ls.kept.size());
    if (ls.kept.empty()) return x + w0_ * r;
    Vec next = x_tilde;
    for (size_t j = 0; j < ls.kept.size(); ++j) next += ls.alpha[j] * *W[ls.kept[j]];
    return next;
  }

 private:
  struct Step {
    std::vector<Vec> dr, dx;
  };
  double w0_;
  int reuse_;
  double filter_;
  std::vector<Vec> r_, xt_;  // this step's residuals and outputs
  std::deque<Step> old_;     // earlier steps' columns, newest first
  int columns_ = 0;
};

/// IQN-IMVJ (Lindner, Mehl, Scheufele & Uekermann 2015, SIAM J. Sci. Comput. 37:S145 — preCICE's
/// "IQN-IMVJ"): the inverse Jacobian J of the step (d x~ = J d r) is the previous steps' J_prev corrected
/// by this step's columns with the least change, J = J_prev + (W - J_prev V)(V^T V)^-1 V^T, and
/// x_{k+1} = x~_k - J r_k = x~_k + W alpha + J_prev(-r_k - V alpha) with alpha the least-squares
/// coefficients of ILS. At the end of a step J becomes J_prev (a dense n x n matrix, n the interface
/// unknowns: a few hundred here). The first step, without J_prev, is ILS without reuse.
class IqnImvj final : public Acceleration {
 public:
  IqnImvj(double w0, double filter) : w0_(w0), filter_(filter) {}
  std::string type() const override { return "iqn_imvj"; }
  int model_columns() const override { return columns_; }
  void serialize(StateArchive& ar) override { ar.io(r_, xt_, J_, columns_); }

  void begin_step() override {
    r_.clear();
    xt_.clear();
  }

  void end_step() override {
    if (r_.size() < 2) return;
    std::vector<Vec> dr, dx;
    const FilteredLeastSquares ls = step_model(r_.back(), dr, dx);
    const Eigen::Index n = r_.back().size();
    if (J_.rows() != n) J_ = Eigen::MatrixXd::Zero(n, n);
    // J += (W - J_prev V) R^-1 Q^T over the kept columns (row i of R^-1 Q^T's transpose: R^-1 applied to
    // the i-th entries of the q's).
    const size_t m = ls.kept.size();
    Eigen::MatrixXd Z(m, n);  // R^-1 Q^T
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::vector<double> zi = ls.back_substitute([&](size_t j) { return ls.Q[j][i]; });
      for (size_t j = 0; j < m; ++j) Z(static_cast<Eigen::Index>(j), i) = zi[j];
    }
    Eigen::MatrixXd D(n, m);  // W - J_prev V (kept columns)
    for (size_t j = 0; j < m; ++j) D.col(static_cast<Eigen::Index>(j)) = dx[ls.kept[j]] - J_ * dr[ls.kept[j]];
    J_ += D * Z;
  }

  void reset() override {
    J_.resize(0, 0);
    r_.clear();
    xt_.clear();
    columns_ = 0;
  }

  Vec update(const Vec& x, const Vec& x_tilde) override {
    const Vec r = x_tilde - x;
    if (!r_.empty() && r_.back().size() != r.size())
      throw SolverError("iqn_imvj: the interface changed size within a step");
    if (J_.size() && J_.rows() != r.size()) J_.resize(0, 0);  // new interface: old Jacobian void
    r_.push_back(r);
    xt_.push_back(x_tilde);
    std::vector<Vec> dr, dx;
    const FilteredLeastSquares ls = step_model(r, dr, dx);
    columns_ = static_cast<int>(ls.kept.size());
    if (ls.kept.empty() && J_.size() == 0) return x + w0_ * r;
    Vec next = x_tilde;
    Vec rest = -r;  // -r - V alpha
    for (size_t j = 0; j < ls.kept.size(); ++j) {
      next += ls.alpha[j] * dx[ls.kept[j]];
      rest -= ls.alpha[j] * dr[ls.kept[j]];
    }
    if (J_.size()) next += J_ * rest;
    return next;
  }

 private:
  /// This step's difference columns (into dr, dx) and their least-squares model for residual r.
  FilteredLeastSquares step_model(const Vec& r, std::vector<Vec>& dr, std::vector<Vec>& dx) const {
    step_differences(r_, xt_, dr, dx);
    std::vector<const Vec*> V;
    for (const Vec& v : dr) V.push_back(&v);
    return FilteredLeastSquares(V, r, filter_);
  }

  double w0_, filter_;
  std::vector<Vec> r_, xt_;
  Eigen::MatrixXd J_;  // previous steps' inverse Jacobian (empty before the first converged step)
  int columns_ = 0;
};

const char* const kInitialRelaxationDoc = "Relaxation factor of the first pass, in (0, 1].";
const char* const kFilterDoc =
    "Columns of the least-squares system whose share falls below this are dropped (QR filter), in (0, 1).";

const KeyTable kConstantKeys("/couplings/*/acceleration (type constant)",
                             "Constant under-relaxation of the interface positions.",
                             {{"type", "constant", "`constant`."},
                              {"relaxation", 0.5, "Relaxation factor, in (0, 1]."}});

const KeyTable kAitkenKeys("/couplings/*/acceleration (type aitken)",
                           "Aitken's dynamic relaxation (the default acceleration).",
                           {{"type", "aitken", "`aitken`."}, {"initial_relaxation", 0.5, kInitialRelaxationDoc}});

const KeyTable kIqnIlsKeys("/couplings/*/acceleration (type iqn_ils)",
                           "Interface quasi-Newton with an inverse Jacobian from least squares (IQN-ILS).",
                           {{"type", "iqn_ils", "`iqn_ils`."},
                            {"initial_relaxation", 0.1, kInitialRelaxationDoc},
                            {"reuse_steps", 8, "Earlier steps whose iterates are reused in the least squares."},
                            {"filter", 1e-8, kFilterDoc}});

const KeyTable kIqnImvjKeys("/couplings/*/acceleration (type iqn_imvj)",
                            "Interface quasi-Newton with a multi-vector Jacobian kept between steps (IQN-IMVJ).",
                            {{"type", "iqn_imvj", "`iqn_imvj`."},
                             {"initial_relaxation", 0.1, kInitialRelaxationDoc},
                             {"filter", 1e-8, kFilterDoc}});

}  // namespace

std::unique_ptr<Acceleration> make_acceleration(Params p) {
  if (!p.json().is_object() || !p.has("type")) p.fail("type", "required key is missing");
  const std::string type = p.choice("type", {"constant", "aitken", "iqn_ils", "iqn_imvj"});
  if (type == "constant") {
    p.validate(kConstantKeys);
    const double w = p.positive("relaxation");
    if (w > 1) p.fail("relaxation", "must lie in (0, 1]");
    return std::make_unique<ConstantRelaxation>(w);
  }
  if (type == "aitken") {
    p.validate(kAitkenKeys);
    const double w = p.positive("initial_relaxation");
    if (w > 1) p.fail("initial_relaxation", "must lie in (0, 1]");
    return std::make_unique<Aitken>(w);
  }
  if (type == "iqn_ils")
    p.validate(kIqnIlsKeys);
  else
    p.validate(kIqnImvjKeys);
  const double w = p.positive("initial_relaxation");
  if (w > 1) p.fail("initial_relaxation", "must lie in (0, 1]");
  const double filter = p.positive("filter");
  if (filter >= 1) p.fail("filter", "must lie in (0, 1)");
  if (type == "iqn_imvj") return std::make_unique<IqnImvj>(w, filter);
  return std::make_unique<IqnIls>(w, p.integer("reuse_steps", 0), filter);
}

}  // namespace lagfsi::fsi
