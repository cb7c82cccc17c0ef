#pragma once
/// @file partition.hpp
/// The particles divided among processes by space, and each process's share of the Delaunay triangulation: the
/// geometric core of a distributed PFEM remeshing (each process meshes its own particles and a ghost layer, and the
/// shares together are the triangulation of the whole cloud).
///
/// Partition: recursive coordinate bisection (Berger & Bokhari 1987): the points are cut across the longer side of
/// their bounding box so that the two sides hold points in proportion to the parts they will be divided into, and
/// each side is cut again, down to one part per box. The boxes tile the plane (the outer ones are unbounded, each
/// box half-open: [lo, hi)), so every point of the plane lies in exactly one part.
///
/// Shares: a part triangulates its own points and its ghosts, the points within `halo` of its box, and keeps the
/// triangles whose circumcentre lies in its box and whose circumradius is at most `halo`. Such a triangle's
/// circumdisc lies in the box grown by the halo, where the part has every point of the cloud, so the disc is empty
/// of the cloud's points exactly when it is empty of the part's: the kept triangles are exactly the triangles of
/// the whole cloud's Delaunay triangulation with R <= halo whose circumcentre is in the box. Over the parts, each
/// such triangle is kept once (its circumcentre is in one box), and no other. The PFEM keeps no element larger than
/// alpha h (the alpha test) or separation_alpha h (the advected detection), so a halo of that size loses none.
/// Points on one circle are triangulated by CGAL's symbolic perturbation (Devillers & Teillaud 2011), which
/// depends on the points alone, not on which others are present: a lattice's squares are cut the same way in
/// every share and in the whole. The circumcentre is computed from the triangle's vertices in increasing index
/// order, so that every share computes the same bits.
#include <lagfsi/types.hpp>

#include <array>
#include <utility>
#include <vector>

namespace lagfsi::meshing {

class SpacePartition {
 public:
  /// Divides `points` into `parts` (>= 1) boxes; throws std::invalid_argument for parts < 1.
  SpacePartition(const std::vector<Vec2>& points, int parts);
  int parts() const { return static_cast<int>(boxes_.size()); }
  /// The part of each point given to the constructor.
  const std::vector<int>& owner() const { return owner_; }
  /// The part whose box holds x.
  int part_of(const Vec2& x) const;
  /// A part's box [lo, hi) (infinite coordinates on the outer sides).
  const std::pair<Vec2, Vec2>& box(int part) const { return boxes_.at(static_cast<size_t>(part)); }
  /// The points (of those given to the constructor, at their positions `points`) within `halo` of the part's box
  /// and not in the part: its ghosts.
  std::vector<Index> ghosts(const std::vector<Vec2>& points, int part, double halo) const;
  /// The points a part triangulates: its own (in increasing index), then its ghosts; `ghost_count` (optional)
  /// receives how many of them are ghosts.
  std::vector<Index> local(const std::vector<Vec2>& points, int part, double halo, Index* ghost_count = nullptr) const;

 private:
  /// A cut: x[axis] < at goes to `low`, the rest to `high` (a negative child -1 - k is part k).
  struct Cut {
    int axis = 0;
    double at = 0;
    int low = -1, high = -1;
  };
  int divide(std::vector<Index>& ids, size_t from, size_t to, int parts, const std::vector<Vec2>& points,
             std::pair<Vec2, Vec2> box);
  std::vector<Cut> cuts_;
  std::vector<std::pair<Vec2, Vec2>> boxes_;
  std::vector<int> owner_;
  int root_ = -1;
};

/// A part's share of the Delaunay triangulation of `points` (global indices, counter-clockwise): the triangles
/// of the part's points and ghosts whose circumcentre is in the part's box and whose circumradius is at most
/// `halo` (see the file comment). `ghost_count` (optional) receives the number of ghosts it used.
std::vector<std::array<Index, 3>> part_delaunay(const std::vector<Vec2>& points, const SpacePartition& partition,
                                                int part, double halo, Index* ghost_count = nullptr);

/// The circumcentre and circumradius of the triangle (a, b, c) of `points`, computed from its vertices in
/// increasing index order (the same bits whatever the triangle's orientation); radius infinite for collinear ones.
std::pair<Vec2, double> circumcircle(const std::vector<Vec2>& points, std::array<Index, 3> t);

}  // namespace lagfsi::meshing
