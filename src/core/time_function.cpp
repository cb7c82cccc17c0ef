#include <lagfsi/time_function.hpp>

#include <lagfsi/input_file.hpp>
#include <lagfsi/text.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string_view>

namespace lagfsi {

namespace {

const KeyTable kConstantKeys("time function (type constant)", "f(t) = value.",
                             {{"type", "constant", "`constant`."}, {"value", 1.0, "The value."}});

const KeyTable kRampKeys("time function (type ramp)", "f(t) = 0 before t0, rising linearly to 1 at t1, then 1.",
                         {{"type", "ramp", "`ramp`."},
                          {"t0", 0.0, "Start of the ramp (s)."},
                          {"t1", nullptr, "End of the ramp (s), after t0."}});

const KeyTable kSinusoidKeys("time function (type sinusoid)", "f(t) = amplitude sin(2 pi frequency t + phase).",
                             {{"type", "sinusoid", "`sinusoid`."},
                              {"amplitude", 1.0, "Amplitude."},
                              {"frequency", nullptr, "Frequency (Hz), positive."},
                              {"phase", 0.0, "Phase (rad)."}});

/// The keys of a wave maker's time function (piston_wavemaker, flap_wavemaker).
std::vector<KeyDecl> wavemaker_keys(const char* type, const char* depth) {
  return {{"type", type, std::string("`") + type + "`."},
          {"height", nullptr, "The wave height H (m), trough to crest, positive."},
          {"period", nullptr, "The wave period T (s), positive."},
          {"depth", nullptr, depth},
          {"gravity", 9.81, "The gravity g (m/s^2) of the dispersion relation."},
          {"ramp_periods", 2.0, "Length of the smooth start in periods (at least 1)."}};
}

const KeyTable kWavemakerKeys(
    "time function (type piston_wavemaker)",
    "The displacement (m) of a piston wave maker that makes regular waves of a given height and period in water of "
    "a given depth, by linear wave-maker theory (Biesel & Suquet 1951): x(t) = (S/2) r(t) sin(2 pi t / T) with the "
    "stroke S = H (sinh 2kd + 2kd) / (2 (cosh 2kd - 1)), omega^2 = g k tanh kd, and a half-cosine ramp r over the "
    "first periods. Use it as a wall's prescribed displacement with \"value\": [1, 0].",
    wavemaker_keys("piston_wavemaker", "The still-water depth d (m) at the paddle, positive."));

const KeyTable kFlapKeys(
    "time function (type flap_wavemaker)",
    "The angle (rad) of a flap wave maker hinged on the floor that makes regular waves of a given height and period "
    "in water of a given depth, by linear wave-maker theory (Biesel & Suquet 1951): theta(t) = theta0 r(t) "
    "sin(2 pi t / T) with the stroke at the still-water level S = 2 d tan(theta0) from H / S = 4 (sinh kd / kd) "
    "(kd sinh kd - cosh kd + 1) / (sinh 2kd + 2kd), omega^2 = g k tanh kd, and a half-cosine ramp r over the first "
    "periods. Use it as a wall's prescribed_rotation about the hinge; \"value\": -1 turns a paddle at the flume's "
    "left end towards +x at the surface for a positive angle.",
    wavemaker_keys("flap_wavemaker", "The still-water depth d (m) at the paddle (the hinge's depth), positive."));

const KeyTable kTableKeys("time function (type table)",
                          "f(t) interpolated linearly in a table of (time, value) rows, constant beyond its ends.",
                          {{"type", "table", "`table`."},
                           {"file", nullptr,
                            "Text file (relative to the case file) of rows `time, value` (',' or spaces; '#' "
                            "comments; an optional header line); times increasing."}});

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

/// A wave maker's motion for regular waves of height H and period T in water of depth d, by linear wave-maker
/// theory (Biesel & Suquet 1951; Dean & Dalrymple 1991, section 6.2): the stroke S at the still-water level from
///   piston:  H / S = 2 (cosh 2kd - 1) / (sinh 2kd + 2kd),
///   flap hinged on the floor:  H / S = 4 (sinh kd / kd) (kd sinh kd - cosh kd + 1) / (sinh 2kd + 2kd),
/// omega^2 = g k tanh kd; the piston's displacement x(t) = (S / 2) r(t) sin(omega t), the flap's angle
/// theta(t) = atan(S / (2 d)) r(t) sin(omega t), with the ramp r = (1 - cos(pi t / t_r)) / 2 over the first t_r
/// seconds.
class Wavemaker final : public TimeFunction {
 public:
  Wavemaker(bool flap, double height, double period, double depth, double g, double ramp)
      : w_(2.0 * std::numbers::pi / period), tr_(ramp) {
    // The dispersion relation by Newton's method from the deep-water guess (monotone in k: converges).
    double k = w_ * w_ / g;
    for (int it = 0; it < 100; ++it) {
      const double th = std::tanh(k * depth), f = g * k * th - w_ * w_;
      const double df = g * th + g * k * depth * (1 - th * th);
      const double dk = f / df;
      k -= dk;
      if (std::abs(dk) < 1e-14 * k) break;
    }
    const double kd = k * depth, kd2 = 2 * kd;
    if (!flap) {
      const double stroke = height * (std::sinh(kd2) + kd2) / (2 * (std::cosh(kd2) - 1));
      amplitude_ = 0.5 * stroke;
      return;
    }
    const double ratio = 4 * (std::sinh(kd) / kd) * (kd * std::sinh(kd) - std::cosh(kd) + 1) / (std::sinh(kd2) + kd2);
    amplitude_ = std::atan(height / ratio / (2 * depth));
  }
  double value(double t) const override {
    const double r = t <= 0 ? 0.0 : t >= tr_ ? 1.0 : 0.5 * (1 - std::cos(std::numbers::pi * t / tr_));
    return amplitude_ * r * std::sin(w_ * t);
  }
  double integral(double t) const override {
    // int_0^t r(s) sin(w s) ds: with a = pi / t_r < w, (1 - cos w t) / (2w) - (1/4) [(1 - cos (w + a) t) / (w + a)
    // + (1 - cos (w - a) t) / (w - a)] during the ramp, then the ramp's value plus (cos w t_r - cos w t) / w.
    if (t <= 0) return 0.0;
    const double a = std::numbers::pi / tr_;
    const auto ramp = [&](double s) {
      return (1 - std::cos(w_ * s)) / (2 * w_) -
             0.25 * ((1 - std::cos((w_ + a) * s)) / (w_ + a) + (1 - std::cos((w_ - a) * s)) / (w_ - a));
    };
    const double i = t <= tr_ ? ramp(t) : ramp(tr_) + (std::cos(w_ * tr_) - std::cos(w_ * t)) / w_;
    return amplitude_ * i;
  }

 private:
  double w_, tr_, amplitude_ = 0;  // the motion's amplitude: S / 2 (piston, m) or theta0 (flap, rad)
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

/// One number of a table row: the whole field must be a finite number in C notation ("1.5", "-2e-3",
/// "+4"); nothing before or after it.
bool parse_number(std::string_view field, double& x) {
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return false;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), x);
  return ec == std::errc() && end == field.data() + field.size() && std::isfinite(x);
}

std::string_view trim(std::string_view s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string_view::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

/// The fields of a data row: separated by commas when the row has one (spaces around them allowed), by
/// spaces or tabs otherwise.
std::vector<std::string_view> split_row(std::string_view row) {
  std::vector<std::string_view> fields;
  if (row.find(',') != std::string_view::npos) {
    size_t a = 0;
    for (;;) {
      const size_t b = row.find(',', a);
      fields.push_back(trim(row.substr(a, b == std::string_view::npos ? std::string_view::npos : b - a)));
      if (b == std::string_view::npos) break;
      a = b + 1;
    }
  } else {
    size_t a = row.find_first_not_of(" \t");
    while (a != std::string_view::npos) {
      const size_t b = row.find_first_of(" \t", a);
      fields.push_back(row.substr(a, b == std::string_view::npos ? std::string_view::npos : b - a));
      a = b == std::string_view::npos ? b : row.find_first_not_of(" \t", b);
    }
  }
  return fields;
}

/// A table: rows "time, value" (two numbers separated by a comma or by spaces), '#' comment lines and
/// blank lines; one header line (text, e.g. "time,value") allowed before the first row. Everything else is
/// an error naming FILE:LINE: a ';' (a spreadsheet's separator), decimal commas ("0,5"), a third column,
/// text in a row, a non-finite value, times that do not increase.
std::unique_ptr<TimeFunction> read_table(const Params& p, const std::filesystem::path& base_dir) {
  std::filesystem::path file = p.string("file");
  if (file.is_relative()) file = base_dir / file;
  const std::string name = echo(file.string(), 200);
  std::string text;
  try {
    text = read_regular_file(file, kMaxTableFileBytes);
  } catch (const InputFileError& e) {
    p.fail("file", "'" + name + "' " + e.what());
  }
  std::vector<double> t, f;
  bool header_allowed = true;
  size_t lineno = 0;
  std::string_view rest = text;
  while (!rest.empty()) {
    ++lineno;
    const size_t nl = rest.find('\n');
    std::string_view line = rest.substr(0, nl);
    rest = nl == std::string_view::npos ? std::string_view{} : rest.substr(nl + 1);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string_view row = trim(line);
    if (row.empty() || row.front() == '#') continue;
    auto bad = [&](const std::string& why) {
      // "0,5" between digits: a decimal comma, read as a separator.
      bool digit_comma_digit = false;
      for (size_t k = 1; k + 1 < row.size(); ++k)
        digit_comma_digit =
            digit_comma_digit || (row[k] == ',' && std::isdigit(static_cast<unsigned char>(row[k - 1])) &&
                                  std::isdigit(static_cast<unsigned char>(row[k + 1])));
      p.fail("file", name + ":" + std::to_string(lineno) + ": " + why +
                         (digit_comma_digit ? " (decimal commas? write 0.5, not 0,5)" : "") + " (found '" + echo(row) +
                         "')");
    };
    if (row.find(';') != std::string_view::npos) bad("';' is not a separator: use ',' or spaces");
    const auto fields = split_row(row);
    std::vector<double> x(fields.size());
    bool numbers = true;
    for (size_t k = 0; k < fields.size(); ++k) numbers = numbers && parse_number(fields[k], x[k]);
    if (!numbers) {
      // Only the first line that is not a comment may be a header, and a header holds no number.
      bool any_number = false;
      for (size_t k = 0; k < fields.size(); ++k) any_number = any_number || parse_number(fields[k], x[k]);
      if (header_allowed && !any_number && valid_utf8(row)) {
        header_allowed = false;
        continue;
      }
      bad("expected two numbers (time, value) separated by ',' or spaces");
    }
    header_allowed = false;
    if (fields.size() != 2) {
      bad("expected two numbers (time, value), found " + std::to_string(fields.size()));
    }
    if (!t.empty() && x[0] <= t.back()) bad("times must increase");
    t.push_back(x[0]);
    f.push_back(x[1]);
  }
  if (t.size() < 2) p.fail("file", name + ": needs at least two rows (time, value)");
  return std::make_unique<Table>(std::move(t), std::move(f));
}

}  // namespace

std::shared_ptr<TimeFunction> constant_function(double c) { return std::make_shared<Constant>(c); }

std::unique_ptr<TimeFunction> make_time_function(Params p, const std::filesystem::path& base_dir) {
  if (!p.json().is_object()) p.fail("expected an object with a \"type\"");
  if (!p.has("type")) p.fail("type", "required key is missing");
  const std::string type =
      p.choice("type", {"constant", "ramp", "sinusoid", "table", "piston_wavemaker", "flap_wavemaker"});
  if (type == "constant") {
    p.validate(kConstantKeys);
    return std::make_unique<Constant>(p.number("value"));
  }
  if (type == "ramp") {
    p.validate(kRampKeys);
    const double t0 = p.number("t0"), t1 = p.number("t1");
    if (!(t1 > t0)) p.fail("t1", "must be greater than t0");
    return std::make_unique<Ramp>(t0, t1);
  }
  if (type == "sinusoid") {
    p.validate(kSinusoidKeys);
    return std::make_unique<Sinusoid>(p.number("amplitude"), p.positive("frequency"), p.number("phase"));
  }
  if (type == "piston_wavemaker" || type == "flap_wavemaker") {
    const bool flap = type == "flap_wavemaker";
    p.validate(flap ? kFlapKeys : kWavemakerKeys);
    const double ramp = p.positive("ramp_periods");
    if (ramp < 1) p.fail("ramp_periods", "must be at least 1");
    const double period = p.positive("period");
    return std::make_unique<Wavemaker>(flap, p.positive("height"), period, p.positive("depth"), p.positive("gravity"),
                                       ramp * period);
  }
  p.validate(kTableKeys);
  return read_table(p, base_dir);
}

}  // namespace lagfsi
