#pragma once
/// @file point_grid.hpp (private to src/fluid)
/// A hash grid of points for the proximity tests of building the particle set (fluid_input.cpp,
/// fluid_walls.cpp).
#include <lagfsi/types.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <unordered_map>
#include <vector>

namespace lagfsi::fluid {

/// Points hashed on a square grid of cell size `cell`: "is there a point within r <= cell of p" in O(1), for
/// building the particle set (shared wall corners, fluid particles next to walls or on a region's border),
/// which compared every pair before (hours at a millionth of the default spacing).
class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell) {}
  void add(const Vec2& p, Index id) { cells_[key(std::floor(p.x() / cell_), std::floor(p.y() / cell_))].push_back(id); }
  /// The last added point within r of p among `pts`, or -1.
  Index find(const Vec2& p, double r, const std::vector<Vec2>& pts) const {
    const double cx = std::floor(p.x() / cell_), cy = std::floor(p.y() / cell_);
    Index found = -1;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (Index j : it->second)
          if ((pts[static_cast<size_t>(j)] - p).norm() < r) found = std::max(found, j);
      }
    return found;
  }

 private:
  struct Key {
    double x, y;
    bool operator==(const Key& o) const { return x == o.x && y == o.y; }
  };
  struct Hash {
    size_t operator()(const Key& k) const { return std::hash<double>()(k.x) * 1000003u ^ std::hash<double>()(k.y); }
  };
  static Key key(double x, double y) { return {x, y}; }
  double cell_;
  std::unordered_map<Key, std::vector<Index>, Hash> cells_;
};

}  // namespace lagfsi::fluid
