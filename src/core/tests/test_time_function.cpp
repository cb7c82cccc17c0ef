// Time functions (time_function.hpp): each one's integral is the integral of its value, and the piston and flap
// wave makers' strokes are linear wave-maker theory's for the height asked (Dean & Dalrymple 1991, section 6.2).
#include <lagfsi/error.hpp>
#include <lagfsi/time_function.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace {

using lagfsi::Json;
using lagfsi::Params;

std::unique_ptr<lagfsi::TimeFunction> make(const Json& j) {
  return lagfsi::make_time_function(Params(j, "case.json", "/f"), ".");
}

/// The wave number k of omega^2 = g k tanh kd for the period T and the depth d, by bisection.
double wavenumber(double T, double d, double g = 9.81) {
  const double w = 2 * std::numbers::pi / T;
  double lo = 1e-6, hi = 100;
  for (int i = 0; i < 200; ++i) {
    const double k = 0.5 * (lo + hi);
    (g * k * std::tanh(k * d) > w * w ? hi : lo) = k;
  }
  return 0.5 * (lo + hi);
}

/// Simpson's rule of f over [0, t] with n (even) intervals.
double simpson(const lagfsi::TimeFunction& f, double t, int n = 20000) {
  const double h = t / n;
  double s = f.value(0) + f.value(t);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * f.value(i * h);
  return s * h / 3;
}

TEST(TimeFunction, EachIntegralIsTheIntegralOfItsValue) {
  for (const Json& j : {Json{{"type", "ramp"}, {"t0", 0.5}, {"t1", 1.5}},
                        Json{{"type", "sinusoid"}, {"amplitude", 2.0}, {"frequency", 1.3}, {"phase", 0.4}},
                        Json{{"type", "piston_wavemaker"}, {"height", 0.05}, {"period", 1.2}, {"depth", 0.4}},
                        Json{{"type", "flap_wavemaker"}, {"height", 0.05}, {"period", 1.2}, {"depth", 0.4}}}) {
    const auto f = make(j);
    for (double t : {0.3, 1.0, 2.0, 2.9, 5.0})
      EXPECT_NEAR(f->integral(t), simpson(*f, t), 1e-7) << j.dump() << " t " << t;
  }
}

TEST(TimeFunction, APistonWavemakersStrokeIsLinearTheorysForTheHeight) {
  // Depth 0.4 m, period 1.2 s: k from omega^2 = g k tanh kd by bisection, then H / S = 2 (cosh 2kd - 1) /
  // (sinh 2kd + 2kd); after the ramp (two periods) the paddle swings between -S/2 and S/2.
  const double H = 0.05, T = 1.2, d = 0.4, g = 9.81;
  const double kd2 = 2 * wavenumber(T, d, g) * d;
  const double stroke = H * (std::sinh(kd2) + kd2) / (2 * (std::cosh(kd2) - 1));
  const auto f = make({{"type", "piston_wavemaker"}, {"height", H}, {"period", T}, {"depth", d}});
  EXPECT_NEAR(f->value(2 * T + T / 4), 0.5 * stroke, 1e-9 * stroke);
  EXPECT_NEAR(f->value(3 * T + 3 * T / 4), -0.5 * stroke, 1e-9 * stroke);
  EXPECT_NEAR(f->value(0), 0.0, 1e-15);
  // The ramp: smaller swings before it ends.
  EXPECT_LT(std::abs(f->value(T / 4)), 0.5 * 0.5 * stroke);
  // In shallow water the stroke tends to H / kd (the paddle pushes the whole depth).
  const auto shallow = make({{"type", "piston_wavemaker"}, {"height", 0.01}, {"period", 20.0}, {"depth", 0.1}});
  const double k_shallow = 2 * std::numbers::pi / 20.0 / std::sqrt(g * 0.1);
  EXPECT_NEAR(shallow->value(2 * 20.0 + 5.0), 0.5 * 0.01 / (k_shallow * 0.1), 0.01 * 0.5 * 0.01 / (k_shallow * 0.1));
}

TEST(TimeFunction, AFlapWavemakersAngleIsLinearTheorysForTheHeight) {
  // A flap hinged on the floor, depth 0.4 m, period 1.2 s: H / S = 4 (sinh kd / kd) (kd sinh kd - cosh kd + 1) /
  // (sinh 2kd + 2kd) with S the stroke at the still-water level; the angle swings between -+atan(S / (2d)).
  const double H = 0.04, T = 1.2, d = 0.4, g = 9.81;
  const double kd = wavenumber(T, d, g) * d;
  const double ratio = 4 * std::sinh(kd) / kd * (kd * std::sinh(kd) - std::cosh(kd) + 1) / (std::sinh(2 * kd) + 2 * kd);
  const double theta0 = std::atan(H / ratio / (2 * d));
  const auto f = make({{"type", "flap_wavemaker"}, {"height", H}, {"period", T}, {"depth", d}});
  EXPECT_NEAR(f->value(2 * T + T / 4), theta0, 1e-9 * theta0);
  EXPECT_NEAR(f->value(3 * T + 3 * T / 4), -theta0, 1e-9 * theta0);
  // A flap moves less water than a piston of the same stroke: it needs the larger stroke for the same height.
  const auto piston = make({{"type", "piston_wavemaker"}, {"height", H}, {"period", T}, {"depth", d}});
  EXPECT_GT(2 * d * std::tan(theta0), 2 * piston->value(2 * T + T / 4));
  // In shallow water (kd -> 0) H / S -> kd / 2, half the piston's kd.
  const auto shallow = make({{"type", "flap_wavemaker"}, {"height", 0.01}, {"period", 20.0}, {"depth", 0.1}});
  const double kds = 2 * std::numbers::pi / 20.0 / std::sqrt(g * 0.1) * 0.1;
  EXPECT_NEAR(std::tan(shallow->value(2 * 20.0 + 5.0)) * 2 * 0.1, 0.01 / (0.5 * kds), 0.02 * 0.01 / (0.5 * kds));
}

TEST(TimeFunction, AShortRampIsAnErrorNamingTheKey) {
  try {
    make({{"type", "piston_wavemaker"}, {"height", 0.05}, {"period", 1.2}, {"depth", 0.4}, {"ramp_periods", 0.5}});
    FAIL() << "no error";
  } catch (const lagfsi::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/f/ramp_periods"), std::string::npos) << e.what();
  }
}

}  // namespace
