#include <lagfsi/time_function.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

namespace lagfsi {

namespace {

class Constant final : public TimeFunction {
 public:
  explicit Constant(double c) : c_(c) {}
  double value(double) const override { return c_; }
  double integral(double t) const override { return c_ * t; }

 private:
  double c_;
};

class Ramp final : public TimeFunction {
 public:
  Ramp(double t0, double t1) : t0_(t0), t1_(t1) {}
  double value(double t) const override {
    if (t <= t0_) return 0.0;
    if (t >= t1_) return 1.0;
    return (t - t0_) / (t1_ - t0_);
  }
  double integral(double t) const override {
    if (t <= t0_) return 0.0;
    if (t <= t1_) return 0.5 * (t - t0_) * (t - t0_) / (t1_ - t0_);
    return 0.5 * (t1_ - t0_) + (t - t1_);
  }

 private:
  double t0_, t1_;
};

class Sinusoid final : public TimeFunction {
 public:
  Sinusoid(double a, double f, double phi) : a_(a), w_(2.0 * std::numbers::pi * f), phi_(phi) {}
  double value(double t) const override { return a_ * std::sin(w_ * t + phi_); }
  double integral(double t) const override { return a_ / w_ * (std::cos(phi_) - std::cos(w_ * t + phi_)); }

 private:
  double a_, w_, phi_;
};

class Table final : public TimeFunction {
 public:
  Table(std::vector<double> t, std::vector<double> f) : t_(std::move(t)), f_(std::move(f)) {
    cum_.assign(t_.size(), 0.0);
    for (size_t i = 1; i < t_.size(); ++i) cum_[i] = cum_[i - 1] + 0.5 * (f_[i] + f_[i - 1]) * (t_[i] - t_[i - 1]);
  }
  double value(double t) const override {
    if (t <= t_.front()) return f_.front();
    if (t >= t_.back()) return f_.back();
    const size_t i = std::upper_bound(t_.begin(), t_.end(), t) - t_.begin();
    const double s = (t - t_[i - 1]) / (t_[i] - t_[i - 1]);
    return (1 - s) * f_[i - 1] + s * f_[i];
  }
  double integral(double t) const override {
    // int_0^t: constant extension before the first sample and after the last.
    auto upto = [&](double s) {  // int from t_.front() to s (s within the table)
      const size_t i = std::upper_bound(t_.begin(), t_.end(), s) - t_.begin();
      if (i == 0) return 0.0;
      if (i >= t_.size()) return cum_.back();
      return cum_[i - 1] + 0.5 * (f_[i - 1] + value(s)) * (s - t_[i - 1]);
    };
    auto from_front = [&](double s) {
      if (s <= t_.front()) return f_.front() * (s - t_.front());
      if (s >= t_.back()) return cum_.back() + f_.back() * (s - t_.back());
      return upto(s);
    };
    return from_front(t) - from_front(0.0);
  }

 private:
  std::vector<double> t_, f_, cum_;
};

std::unique_ptr<TimeFunction> read_table(const Params& p, const std::filesystem::path& base_dir) {
  std::filesystem::path file = p.string("file");
  if (file.is_relative()) file = base_dir / file;
  std::ifstream in(file);
  if (!in) p.fail("file", "cannot open '" + file.string() + "'");
  std::vector<double> t, f;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ls(line);
    double a, b;
    if (!(ls >> a >> b)) {
      if (t.empty()) continue;  // a header line
      p.fail("file", file.string() + " line " + std::to_string(lineno) + ": expected two numbers");
    }
    if (!std::isfinite(a) || !std::isfinite(b))
      p.fail("file", file.string() + " line " + std::to_string(lineno) + ": non-finite value");
    if (!t.empty() && a <= t.back())
      p.fail("file", file.string() + " line " + std::to_string(lineno) + ": times must increase");
    t.push_back(a);
    f.push_back(b);
  }
  if (t.size() < 2) p.fail("file", file.string() + ": needs at least two rows (time, value)");
  return std::make_unique<Table>(std::move(t), std::move(f));
}

}  // namespace

std::shared_ptr<TimeFunction> constant_function(double c) { return std::make_shared<Constant>(c); }

std::unique_ptr<TimeFunction> make_time_function(Params p, const std::filesystem::path& base_dir) {
  if (!p.json().is_object()) p.fail("expected an object with a \"type\"");
  if (!p.has("type")) p.fail("type", "required key is missing");
  const std::string type = p.choice("type", {"constant", "ramp", "sinusoid", "table"});
  if (type == "constant") {
    p.validate({{"type", "constant"}, {"value", 1.0}});
    return std::make_unique<Constant>(p.number("value"));
  }
  if (type == "ramp") {
    p.validate({{"type", "ramp"}, {"t0", 0.0}, {"t1", nullptr}});
    const double t0 = p.number("t0"), t1 = p.number("t1");
    if (!(t1 > t0)) p.fail("t1", "must be greater than t0");
    return std::make_unique<Ramp>(t0, t1);
  }
  if (type == "sinusoid") {
    p.validate({{"type", "sinusoid"}, {"amplitude", 1.0}, {"frequency", nullptr}, {"phase", 0.0}});
    return std::make_unique<Sinusoid>(p.number("amplitude"), p.positive("frequency"), p.number("phase"));
  }
  p.validate({{"type", "table"}, {"file", nullptr}});
  return read_table(p, base_dir);
}

}  // namespace lagfsi
