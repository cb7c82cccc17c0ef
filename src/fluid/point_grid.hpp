#pragma once
/// @file point_grid.hpp (private to src/fluid)
/// A hash grid of points for the proximity tests of building the particle set (fluid_input.cpp,
/// fluid_walls.cpp) and of the particle management of every remesh (particle_management.cpp).
#include <lagfsi/types.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lagfsi::fluid {

/// Points hashed on a square grid of cell size `cell`: "is there a point within r <= cell of p" in O(1), for
/// building the particle set (shared wall corners, fluid particles next to walls or on a region's border),
/// which compared every pair before (hours at a millionth of the default spacing), and for the close pairs of
/// the particle management at every remesh.
/// The cells are an open-addressing table (linear probing, power-of-two capacity) of integer cell coordinates,
/// each the head of a list of the points in it, kept in one array: an add is one probe and one push, a find
/// nine probes. (A std::unordered_map of a vector per cell, hashing the cells' coordinates as doubles, took
/// 40 % of the remesh with the fluid's conservative defaults at 5e4 particles.)
class PointGrid {
 public:
  /// `expected`: the number of points about to be added (sizes the table; it grows as needed).
  explicit PointGrid(double cell, std::size_t expected = 0) : cell_(cell) {
    std::size_t cap = 16;
    while (cap < 2 * expected) cap *= 2;
    slots_.assign(cap, Slot{});
    nodes_.reserve(expected);
  }
  void add(const Vec2& p, Index id) {
    const Cell c = cell_of(p);
    if (2 * (used_ + 1) > slots_.size()) grow();
    Slot& s = slots_[probe(c)];
    if (s.head < 0) {
      s.cx = c.x;
      s.cy = c.y;
      ++used_;
    }
    nodes_.push_back({id, s.head});
    s.head = static_cast<Index>(nodes_.size() - 1);
  }
  /// The last added point within r of p among `pts` (the largest id), or -1; `except` (optional) is left out.
  Index find(const Vec2& p, double r, const std::vector<Vec2>& pts, Index except = -1) const {
    const Cell c = cell_of(p);
    Index found = -1;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const Slot& s = slots_[probe({c.x + dx, c.y + dy})];
        for (Index k = s.head; k >= 0; k = nodes_[static_cast<std::size_t>(k)].next) {
          const Index j = nodes_[static_cast<std::size_t>(k)].id;
          if (j != except && (pts[static_cast<std::size_t>(j)] - p).norm() < r) found = std::max(found, j);
        }
      }
    return found;
  }

 private:
  struct Cell {
    std::int64_t x, y;
  };
  struct Slot {
    std::int64_t cx = 0, cy = 0;
    Index head = -1;  // -1: empty
  };
  struct Node {
    Index id, next;
  };
  /// The cell of p; coordinates beyond +-2^60 cells are clamped (the points there share cells, and the
  /// distance test still decides).
  Cell cell_of(const Vec2& p) const {
    constexpr double lim = 1152921504606846976.0;  // 2^60
    const auto coord = [&](double v) {
      const double f = std::floor(v / cell_);
      return static_cast<std::int64_t>(f != f ? 0.0 : std::clamp(f, -lim, lim));
    };
    return {coord(p.x()), coord(p.y())};
  }
  /// The slot of cell c: its own, or the empty one where it would go.
  std::size_t probe(const Cell& c) const {
    const std::size_t mask = slots_.size() - 1;
    std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull ^
                      (static_cast<std::uint64_t>(c.y) + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= h >> 29;
    for (std::size_t i = static_cast<std::size_t>(h) & mask;; i = (i + 1) & mask) {
      const Slot& s = slots_[i];
      if (s.head < 0 || (s.cx == c.x && s.cy == c.y)) return i;
    }
  }
  void grow() {
    std::vector<Slot> old(2 * slots_.size(), Slot{});
    old.swap(slots_);
    for (const Slot& s : old)
      if (s.head >= 0) slots_[probe({s.cx, s.cy})] = s;
  }
  double cell_;
  std::vector<Slot> slots_;
  std::vector<Node> nodes_;
  std::size_t used_ = 0;
};

}  // namespace lagfsi::fluid
