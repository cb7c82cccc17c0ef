#pragma once
/// @file dem/dem_walls.hpp
/// Rigid walls of the DEM body: polylines, fixed or translated with a velocity v(t) = v0 f(t) (f a time
/// function, time_function.hpp). A disc touches a segment when the distance d from its centre c to the
/// segment's closest point p is below its radius: overlap r - d, normal n = (c - p)/d; the wall acts as a
/// body of infinite mass and radius (m_eff = m_i, r_eff = r_i) moving with the wall's velocity.
#include <lagfsi/geometry2d.hpp>  // closest_on_segment
#include <lagfsi/params.hpp>
#include <lagfsi/time_function.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi::dem {

struct Wall {
  std::string name;
  std::vector<Vec2> points;                ///< the polyline at t = 0
  Vec2 velocity0 = Vec2::Zero();           ///< v(t) = velocity0 f(t)
  std::shared_ptr<TimeFunction> function;  ///< null: f = 1
  Vec2 offset = Vec2::Zero();              ///< translation at the current time

  /// The translation at time t (velocity0 times the integral of f from 0 to t).
  Vec2 displacement(double t) const;
  Vec2 velocity(double t) const;
  bool moving() const { return velocity0.squaredNorm() > 0; }
  size_t segments() const { return points.size() - 1; }
  Vec2 a(size_t s) const { return points[s] + offset; }
  Vec2 b(size_t s) const { return points[s + 1] + offset; }
};

/// Reads the body's "walls" array: [{"name", "points": [[x, y], ...] (>= 2), "velocity": [vx, vy],
/// "function": {time function}}].
std::vector<Wall> read_walls(Params walls, const std::filesystem::path& base_dir);

}  // namespace lagfsi::dem
