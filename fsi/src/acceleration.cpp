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

 private:
  double w0_, w_ = 0;
  Vec r_prev_;
};

class IqnIls final : public Acceleration {
 public:
  IqnIls(double w0, int reuse, double filter) : w0_(w0), reuse_(reuse), filter_(filter) {}
  std::string type() const override { return "iqn_ils"; }
  int model_columns() const override { return columns_; }

  void begin_step() override {
    r_.clear();
    xt_.clear();
  }

  void end_step() override {
    if (reuse_ <= 0 || r_.size() < 2) return;
    Step s;
    for (size_t i = r_.size() - 1; i >= 1; --i) {  // newest difference first
      s.dr.push_back(r_[i] - r_[i - 1]);
      s.dx.push_back(xt_[i] - xt_[i - 1]);
    }
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
    if (!r_.empty() && r_.back().size() != r.size()) throw SolverError("iqn_ils: the interface changed size within a step");
    if (!old_.empty() && old_.front().dr.front().size() != r.size()) old_.clear();  // new interface: old model void
    r_.push_back(r);
    xt_.push_back(x_tilde);
    // Columns, newest first: this step's differences, then the reused steps' ones.
    std::vector<const Vec*> V, W;
    std::vector<Vec> dr_now, dx_now;
    for (size_t i = r_.size() - 1; i >= 1; --i) {
      dr_now.push_back(r_[i] - r_[i - 1]);
      dx_now.push_back(xt_[i] - xt_[i - 1]);
    }
    for (size_t i = 0; i < dr_now.size(); ++i) {
      V.push_back(&dr_now[i]);
      W.push_back(&dx_now[i]);
    }
    for (const Step& s : old_)
      for (size_t i = 0; i < s.dr.size(); ++i) {
        V.push_back(&s.dr[i]);
        W.push_back(&s.dx[i]);
      }
    // Modified Gram-Schmidt QR of the kept columns, with the filter.
    std::vector<Vec> Q;
    std::vector<std::vector<double>> R;  // R[j] = column j of R (entries 0..j)
    std::vector<size_t> kept;
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
      if (nq < filter_ * norm0) continue;
      rc[Q.size()] = nq;
      Q.push_back(q / nq);
      R.push_back(std::move(rc));
      kept.push_back(c);
    }
    columns_ = static_cast<int>(kept.size());
    if (kept.empty()) return x + w0_ * r;
    // R alpha = -Q^T r (back substitution), then x = x~ + W alpha.
    const size_t m = kept.size();
    std::vector<double> b(m), alpha(m, 0.0);
    for (size_t j = 0; j < m; ++j) b[j] = -Q[j].dot(r);
    for (size_t j = m; j-- > 0;) {
      double s = b[j];
      for (size_t l = j + 1; l < m; ++l) s -= R[l][j] * alpha[l];
      alpha[j] = s / R[j][j];
    }
    Vec next = x_tilde;
    for (size_t j = 0; j < m; ++j) next += alpha[j] * *W[kept[j]];
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

}  // namespace

std::unique_ptr<Acceleration> make_acceleration(Params p) {
  if (!p.json().is_object() || !p.has("type")) p.fail("type", "required key is missing");
  const std::string type = p.choice("type", {"constant", "aitken", "iqn_ils"});
  if (type == "constant") {
    p.validate({{"type", type}, {"relaxation", 0.5}});
    const double w = p.positive("relaxation");
    if (w > 1) p.fail("relaxation", "must lie in (0, 1]");
    return std::make_unique<ConstantRelaxation>(w);
  }
  if (type == "aitken") {
    p.validate({{"type", type}, {"initial_relaxation", 0.5}});
    const double w = p.positive("initial_relaxation");
    if (w > 1) p.fail("initial_relaxation", "must lie in (0, 1]");
    return std::make_unique<Aitken>(w);
  }
  p.validate({{"type", type}, {"initial_relaxation", 0.1}, {"reuse_steps", 8}, {"filter", 1e-8}});
  const double w = p.positive("initial_relaxation");
  if (w > 1) p.fail("initial_relaxation", "must lie in (0, 1]");
  const double filter = p.positive("filter");
  if (filter >= 1) p.fail("filter", "must lie in (0, 1)");
  return std::make_unique<IqnIls>(w, p.integer("reuse_steps", 0), filter);
}

}  // namespace lagfsi::fsi
