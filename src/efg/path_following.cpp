// Load, displacement, generalized displacement control and cylindrical arc length (Yang & Kuo 1994; Crisfield
// 1981/1983), in the form used by the INSANE EFG thesis, with a remedy for the arc length's complex roots. See
// src/efg/include/lagfsi/efg/path_following.hpp.
#include <lagfsi/efg/path_following.hpp>
#include <lagfsi/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace lagfsi::efg {

ControlType PathFollowing::parse(const std::string& name) {
  if (name == "load") return ControlType::load;
  if (name == "displacement") return ControlType::displacement;
  if (name == "generalized_displacement") return ControlType::generalized_displacement;
  if (name == "arc_length") return ControlType::arc_length;
  throw std::invalid_argument("unknown control '" + name + "'");
}

ComplexRoots PathFollowing::parse_complex_roots(const std::string& name) {
  if (name == "real_part") return ComplexRoots::real_part;
  if (name == "normal_plane") return ComplexRoots::normal_plane;
  if (name == "cut_back") return ComplexRoots::cut_back;
  throw std::invalid_argument("unknown complex_roots remedy '" + name + "'");
}

void PathFollowing::fail(const std::string& reason) const {
  throw SolverError(where_.empty() ? reason : where_ + ": " + reason);
}

double PathFollowing::predictor(const Vec& dUP, double scale) {
  scale_ = scale;
  dUP1_cur_ = dUP;
  dlambda_step_ = step_predictor(dUP, scale);
  return dlambda_step_;
}

double PathFollowing::step_predictor(const Vec& dUP, double scale) {
  switch (type_) {
    case ControlType::load: {
      if (steps_ > 0 && dUP1_prev_.size() == dUP.size() && dUP1_prev_.dot(dUP) <= 0) {
        char m[320];
        std::snprintf(m, sizeof m,
                      "load control cannot pass the limit point at load factor %.6g (the tangent response to the "
                      "load turned against the last step's: the stiffness is no longer positive definite); "
                      "follow the path past it with displacement, generalized_displacement or arc_length control",
                      lambda_);
        fail(m);
      }
      return inc_ * scale;
    }
    case ControlType::displacement: {
      const double d = dUP[dof_];
      if (std::abs(d) < 1e-300) fail("displacement control: the controlled dof does not respond to the load");
      return inc_ * scale / d;
    }
    case ControlType::generalized_displacement: {
      if (steps_ == 0) {
        dUP1_first_ = dUP;
        sign_cur_ = 1;
        return inc_ * scale;
      }
      const double den = dUP1_prev_.dot(dUP);
      if (std::abs(den) < 1e-300)
        fail(
            "generalized displacement control: GSP undefined (the response to the reference load vanishes: a load "
            "of zero or next to it?)");
      const double gsp = dUP1_first_.squaredNorm() / den;
      sign_cur_ = sign_ * (gsp < 0 ? -1.0 : 1.0);
      return sign_cur_ * inc_ * scale * std::sqrt(std::abs(gsp));
    }
    case ControlType::arc_length: {
      const double n = dUP.norm();
      if (!(n > 0)) fail("arc length: zero tangent response");
      if (dl_ == 0) dl_ = std::abs(inc_) * n;
      double s = inc_ < 0 ? -1 : 1;  // the first step: the direction the increment's sign asks for
      if (DU_prev_.size() == dUP.size()) s = DU_prev_.dot(dUP) < 0 ? -1 : 1;
      return s * dl_ * scale / n;
    }
  }
  return 0;
}

double PathFollowing::corrector(const Vec& dUP, const Vec& dUQ, const Vec& DU) {
  const double dl = step_corrector(dUP, dUQ, DU);
  dlambda_step_ += dl;
  return dl;
}

double PathFollowing::step_corrector(const Vec& dUP, const Vec& dUQ, const Vec& DU) {
  switch (type_) {
    case ControlType::load:
      return 0.0;
    case ControlType::displacement:
      return -dUQ[dof_] / dUP[dof_];
    case ControlType::generalized_displacement: {
      const Vec& r = steps_ == 0 ? dUP1_cur_ : dUP1_prev_;
      return -r.dot(dUQ) / r.dot(dUP);
    }
    case ControlType::arc_length: {
      const double l = dl_ * scale_;
      const Vec w = DU + dUQ;
      const double a = dUP.squaredNorm(), b = 2 * dUP.dot(w), c = w.squaredNorm() - l * l;
      const double disc = b * b - 4 * a * c;
      if (disc < 0) {
        switch (complex_roots_) {
          case ComplexRoots::cut_back:
            fail("arc length: the constraint has no real root (step too long)");
          case ComplexRoots::real_part:
            ++stats_.complex_root_iterations;
            return -b / (2 * a);
          case ComplexRoots::normal_plane: {
            const double den = DU.dot(dUP);
            if (std::abs(den) < 1e-300) fail("arc length: complex roots and a normal plane parallel to dUP");
            ++stats_.complex_root_iterations;
            return -DU.dot(dUQ) / den;
          }
        }
      }
      const double r1 = (-b + std::sqrt(disc)) / (2 * a), r2 = (-b - std::sqrt(disc)) / (2 * a);
      // The root whose new increment makes the smaller angle with the current one.
      const double c1 = (w + r1 * dUP).dot(DU), c2 = (w + r2 * dUP).dot(DU);
      return c1 >= c2 ? r1 : r2;
    }
  }
  return 0;
}

void PathFollowing::commit(const Vec& DU) {
  if (type_ == ControlType::arc_length && dl_ > 0) {
    const double ratio = DU.norm() / (dl_ * scale_);
    if (std::abs(ratio - 1) > 1e-6) ++stats_.steps_off_constraint;
    stats_.max_increment_ratio = std::max(stats_.max_increment_ratio, ratio);
  }
  dUP1_prev_ = dUP1_cur_;
  DU_prev_ = DU;
  sign_ = sign_cur_;
  lambda_ += dlambda_step_;
  dlambda_step_ = 0;
  ++steps_;
}

}  // namespace lagfsi::efg
