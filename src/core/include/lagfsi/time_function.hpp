#pragma once
/// @file time_function.hpp
/// Scalar functions of time that scale loads and prescribed motions:
///  - {"type": "constant", "value": c}                       f = c (a step load when applied from t = 0)
///  - {"type": "ramp", "t0": a, "t1": b}                     f = 0 before a, linear to 1 at b, 1 after
///  - {"type": "sinusoid", "amplitude": A, "frequency": f, "phase": phi}   f = A sin(2 pi f t + phi)
///  - {"type": "table", "file": "x.csv"}                     piecewise linear in a two-column CSV (time, value);
///                                                           '#' lines are comments; constant beyond the ends
///  - {"type": "piston_wavemaker", "height": H, "period": T, "depth": d}   a piston paddle's displacement for
///                                                           regular waves by linear wave-maker theory
///  - {"type": "flap_wavemaker", "height": H, "period": T, "depth": d}     a flap paddle's angle (rad), the same
/// integral(t) = int_0^t f(s) ds (exact for each type; used for prescribed velocities).
#include <lagfsi/params.hpp>

#include <memory>
#include <vector>

namespace lagfsi {

class TimeFunction {
 public:
  virtual ~TimeFunction() = default;
  virtual double value(double t) const = 0;
  virtual double integral(double t) const = 0;
};

/// f(t) = c.
std::shared_ptr<TimeFunction> constant_function(double c);

/// Builds a time function from its parameters (validated; paths relative to `base_dir`).
std::unique_ptr<TimeFunction> make_time_function(Params p, const std::filesystem::path& base_dir);

}  // namespace lagfsi
