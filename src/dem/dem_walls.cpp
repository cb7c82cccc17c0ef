// Rigid polyline walls of the DEM body (src/dem/include/lagfsi/dem/dem_walls.hpp).
#include <lagfsi/dem/dem_walls.hpp>

namespace lagfsi::dem {

namespace {

const KeyTable kDemWallKeys(
    "/bodies/*/walls/* (dem body)", "A rigid polyline wall, fixed or translated with a velocity v0 f(t).",
    {{"name", "wall", "Wall name; default: wall<index>.", kDerived},
     {"points", nullptr, "The polyline [[x, y], ...] (m), at least 2 points."},
     {"velocity", Json::array({0.0, 0.0}), "Velocity v0 [vx, vy] (m/s)."},
     {"function", Json::object(),
      "Function of time f scaling the velocity (see time function (type constant) and others); {}: 1."}});

}  // namespace

Vec2 Wall::displacement(double t) const {
  if (!moving()) return Vec2::Zero();
  return velocity0 * (function ? function->integral(t) : t);
}

Vec2 Wall::velocity(double t) const {
  if (!moving()) return Vec2::Zero();
  return velocity0 * (function ? function->value(t) : 1.0);
}

std::vector<Wall> read_walls(Params walls, const std::filesystem::path& base_dir) {
  std::vector<Wall> out;
  for (size_t i = 0; i < walls.size(); ++i) {
    Params w = walls.at(i);
    if (!w.json().is_object()) w.fail("expected an object");
    w.validate(kDemWallKeys, {{"name", "wall" + std::to_string(i)}});
    Wall wall;
    wall.name = w.identifier("name");
    wall.points = w.points("points");
    if (wall.points.size() < 2) w.fail("points", "a wall needs at least 2 points");
    for (size_t s = 0; s + 1 < wall.points.size(); ++s)
      if ((wall.points[s + 1] - wall.points[s]).norm() <= 0) w.fail("points", "two consecutive points coincide");
    wall.velocity0 = w.vec2("velocity");
    if (!w.json().at("function").empty()) wall.function = make_time_function(w.at("function"), base_dir);
    out.push_back(std::move(wall));
  }
  return out;
}

}  // namespace lagfsi::dem
