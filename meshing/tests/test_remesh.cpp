// Unit tests of the PFEM remeshing (lagfsi::meshing::remesh, delaunay_triangles, close_fluid_particles,
// oversized_elements). Expected values are computed independently of CGAL: closed-form areas of grids
// and regular polygons, a brute-force Delaunay triangulation (every empty-circumcircle triple), edge
// usage counted with a std::map, circumradii from the circumcentre, areas from Heron's formula.
#include <lagfsi/meshing/remesh.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

using lagfsi::Index;
using lagfsi::Vec2;
using lagfsi::meshing::close_fluid_particles;
using lagfsi::meshing::delaunay_triangles;
using lagfsi::meshing::oversized_elements;
using lagfsi::meshing::ParticleKind;
using lagfsi::meshing::remesh;
using lagfsi::meshing::RemeshResult;
using lagfsi::meshing::RemeshSettings;
using Tri = std::array<Index, 3>;

constexpr double kPi = std::numbers::pi;

struct Cloud {
  std::vector<Vec2> p;
  std::vector<ParticleKind> kind;
  std::vector<double> h;
  Index add(double x, double y, ParticleKind k = ParticleKind::Fluid, double hh = 1.0) {
    p.emplace_back(x, y);
    kind.push_back(k);
    h.push_back(hh);
    return static_cast<Index>(p.size() - 1);
  }
  RemeshResult mesh(double alpha = 1.2) const { return remesh(p, kind, h, RemeshSettings{alpha}); }
};

double signed_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
}

// Circumcentre by solving the perpendicular-bisector system (independent of R = abc / 4A).
Vec2 circumcentre(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = b - a, v = c - a;
  const double d = 2.0 * (u.x() * v.y() - u.y() * v.x());
  const double uu = u.squaredNorm(), vv = v.squaredNorm();
  return a + Vec2((v.y() * uu - u.y() * vv) / d, (u.x() * vv - v.x() * uu) / d);
}

double circumradius(const Vec2& a, const Vec2& b, const Vec2& c) { return (circumcentre(a, b, c) - a).norm(); }

double heron_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double x = (b - a).norm(), y = (c - b).norm(), z = (a - c).norm(), s = 0.5 * (x + y + z);
  return std::sqrt(std::max(0.0, s * (s - x) * (s - y) * (s - z)));
}

// Rotation of a triangle that starts at its smallest index (orientation kept).
Tri canonical(Tri t) {
  while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
  return t;
}

std::set<Tri> canonical_set(const std::vector<Tri>& ts) {
  std::set<Tri> s;
  for (const Tri& t : ts) s.insert(canonical(t));
  return s;
}

// Fluid particles on an edge used by exactly one triangle, counted with a map.
std::vector<std::uint8_t> free_surface_by_edge_count(const Cloud& c, const std::vector<Tri>& tris) {
  std::map<std::pair<Index, Index>, int> uses;
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) ++uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  std::vector<std::uint8_t> fs(c.p.size(), 0);
  for (const auto& [e, count] : uses)
    if (count == 1) {
      if (c.kind[e.first] == ParticleKind::Fluid) fs[e.first] = 1;
      if (c.kind[e.second] == ParticleKind::Fluid) fs[e.second] = 1;
    }
  return fs;
}

bool all_boundary(const Cloud& c, const Tri& t) {
  return c.kind[t[0]] != ParticleKind::Fluid && c.kind[t[1]] != ParticleKind::Fluid &&
         c.kind[t[2]] != ParticleKind::Fluid;
}

void expect_ccw_and_alpha(const Cloud& c, const RemeshResult& r, double alpha) {
  for (const Tri& t : r.triangles) {
    const Vec2 &a = c.p[t[0]], &b = c.p[t[1]], &cc = c.p[t[2]];
    EXPECT_GT(signed_area(a, b, cc), 0.0);
    const double he = (c.h[t[0]] + c.h[t[1]] + c.h[t[2]]) / 3.0;
    EXPECT_LE(circumradius(a, b, cc), alpha * he * (1 + 1e-12));
    EXPECT_FALSE(all_boundary(c, t));
  }
}

// ------------------------------------------------------------------------------------------------ (1)
TEST(Remesh, RegularGridCoversTheRectangleAndFreeSurfaceIsThePerimeter) {
  const int nx = 21, ny = 13;
  const double h = 0.1, x0 = 0.3, y0 = -0.7;
  Cloud c;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) c.add(x0 + i * h, y0 + j * h, ParticleKind::Fluid, h);
  const RemeshResult r = c.mesh(1.2);
  const double exact = (nx - 1) * (ny - 1) * h * h;
  EXPECT_NEAR(r.area, exact, 1e-12 * exact);
  EXPECT_EQ(r.triangles.size(), static_cast<std::size_t>(2 * (nx - 1) * (ny - 1)));
  EXPECT_EQ(r.removed_alpha, 0);
  EXPECT_EQ(r.removed_boundary_only, 0);
  expect_ccw_and_alpha(c, r, 1.2);
  for (const Tri& t : r.triangles) EXPECT_NEAR(signed_area(c.p[t[0]], c.p[t[1]], c.p[t[2]]), 0.5 * h * h, 1e-14);
  ASSERT_EQ(r.free_surface.size(), c.p.size());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const bool perimeter = i == 0 || j == 0 || i == nx - 1 || j == ny - 1;
      EXPECT_EQ(r.free_surface[j * nx + i], perimeter ? 1 : 0) << i << ' ' << j;
      EXPECT_EQ(r.connected[j * nx + i], 1);
    }
  // The grid's right-isosceles triangles have R = h / sqrt(2): the test bites exactly there.
  const RemeshResult just_above = c.mesh(0.7072);
  EXPECT_EQ(just_above.triangles.size(), r.triangles.size());
  const RemeshResult below = c.mesh(0.7070);
  EXPECT_TRUE(below.triangles.empty());
  EXPECT_EQ(below.removed_alpha, 2 * (nx - 1) * (ny - 1));
  EXPECT_EQ(below.area, 0.0);
  for (std::size_t i = 0; i < c.p.size(); ++i) EXPECT_EQ(below.free_surface[i] + below.connected[i], 0);
}

// ------------------------------------------------------------------------------------------------ (2)
TEST(Remesh, SeparateBlocksAreNotConnectedAndIsolatedParticleIsFree) {
  const int m = 6;
  Cloud c;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) c.add(i, j);
  const Index first_b = static_cast<Index>(c.p.size());
  const double gap = 4.0;  // bridging elements have R >= gap / 2 = 2 h > 1.2 h
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) c.add((m - 1) + gap + i, j + 0.5);
  const Index lone = c.add(100.0, 100.0);
  const RemeshResult r = c.mesh(1.2);
  int in_a = 0, in_b = 0;
  for (const Tri& t : r.triangles) {
    const int nb = (t[0] >= first_b) + (t[1] >= first_b) + (t[2] >= first_b);
    EXPECT_TRUE(nb == 0 || nb == 3) << "element bridges the blocks";
    EXPECT_TRUE(t[0] != lone && t[1] != lone && t[2] != lone);
    (nb == 0 ? in_a : in_b)++;
  }
  EXPECT_EQ(in_a, 2 * (m - 1) * (m - 1));
  EXPECT_EQ(in_b, 2 * (m - 1) * (m - 1));
  EXPECT_NEAR(r.area, 2.0 * (m - 1) * (m - 1), 1e-12);
  EXPECT_GT(r.removed_alpha, 0);
  EXPECT_EQ(r.connected[lone], 0);
  EXPECT_EQ(r.free_surface[lone], 0);
  for (Index i = 0; i < lone; ++i) EXPECT_EQ(r.connected[i], 1);
  EXPECT_EQ(r.free_surface, free_surface_by_edge_count(c, r.triangles));
}

// ------------------------------------------------------------------------------------------------ (3)
TEST(Remesh, HollowRingKeepsTheHoleEmptyAndItsInnerParticlesAreFreeSurface) {
  const double h = 0.05;
  const int rings = 6;  // radii 3h .. 8h
  Cloud c;
  std::vector<int> ring_of;
  std::vector<int> count(rings);
  for (int k = 0; k < rings; ++k) {
    const double r = (3 + k) * h;
    count[k] = static_cast<int>(std::lround(2 * kPi * r / h));
    for (int q = 0; q < count[k]; ++q) {
      const double th = 0.37 * k + 2 * kPi * q / count[k];
      c.add(1.0 + r * std::cos(th), 2.0 + r * std::sin(th), ParticleKind::Fluid, h);
      ring_of.push_back(k);
    }
  }
  const RemeshResult r = c.mesh(1.2);
  // The kept elements cover exactly the region between the inner and outer regular polygons.
  auto polygon = [](int n, double rad) { return 0.5 * n * rad * rad * std::sin(2 * kPi / n); };
  const double exact = polygon(count[rings - 1], (2 + rings) * h) - polygon(count[0], 3 * h);
  EXPECT_NEAR(r.area, exact, 1e-12 * exact);
  EXPECT_GT(r.removed_alpha, 0);
  expect_ccw_and_alpha(c, r, 1.2);
  for (const Tri& t : r.triangles) {
    EXPECT_FALSE(ring_of[t[0]] == 0 && ring_of[t[1]] == 0 && ring_of[t[2]] == 0) << "element inside the hole";
    const Vec2 g = (c.p[t[0]] + c.p[t[1]] + c.p[t[2]]) / 3.0;
    EXPECT_GT((g - Vec2(1.0, 2.0)).norm(), 3 * h * std::cos(kPi / count[0]));
  }
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    const bool on_surface = ring_of[i] == 0 || ring_of[i] == rings - 1;
    EXPECT_EQ(r.free_surface[i], on_surface ? 1 : 0) << "particle " << i << " ring " << ring_of[i];
    EXPECT_EQ(r.connected[i], 1);
  }
}

// ------------------------------------------------------------------------------------------------ (4)
TEST(Remesh, WallOnlyElementsAreRemovedAndWallsAreNeverFreeSurface) {
  const int nx = 10, ny = 6;
  Cloud c;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) c.add(i, j + 1);
  for (int i = -2; i <= nx + 1; ++i) {
    c.add(i, 0, ParticleKind::Wall);
    c.add(i + 0.5, -0.9, ParticleKind::Ghost);
  }
  // The wall/ghost strip is made of Delaunay elements that pass the alpha test on their own.
  int strip_candidates = 0;
  for (const Tri& t : delaunay_triangles(c.p))
    if (all_boundary(c, t) && circumradius(c.p[t[0]], c.p[t[1]], c.p[t[2]]) <= 1.2) ++strip_candidates;
  ASSERT_GT(strip_candidates, 0);

  const RemeshResult r = c.mesh(1.2);
  EXPECT_EQ(r.removed_boundary_only, strip_candidates);
  expect_ccw_and_alpha(c, r, 1.2);
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    if (c.kind[i] != ParticleKind::Fluid) {
      EXPECT_EQ(r.free_surface[i], 0);
      continue;
    }
    const int ix = static_cast<int>(i) % nx, jy = static_cast<int>(i) / nx;
    const bool surface = ix == 0 || ix == nx - 1 || jy == ny - 1;  // not the bottom row: it lies on walls
    EXPECT_EQ(r.free_surface[i], surface ? 1 : 0) << ix << ' ' << jy;
  }
  EXPECT_EQ(r.free_surface, free_surface_by_edge_count(c, r.triangles));
  // Every fluid particle and the wall particles under the block are used.
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    if (c.kind[i] == ParticleKind::Fluid ||
        (c.kind[i] == ParticleKind::Wall && c.p[i].x() >= 0 && c.p[i].x() <= nx - 1)) {
      EXPECT_EQ(r.connected[i], 1) << i;
    }
    if (c.kind[i] == ParticleKind::Ghost) {
      EXPECT_EQ(r.connected[i], 0) << i;  // ghosts only touch walls here
    }
  }
}

// ------------------------------------------------------------------------------------------------ (5)
struct BruteForce {
  std::set<Tri> delaunay, kept;
  int removed_alpha = 0, removed_boundary = 0;
};

// Every CCW triple with an empty circumcircle (O(n^3) triples, each emptiness check O(n) with early exit).
BruteForce brute_force(const Cloud& c, double alpha) {
  BruteForce b;
  const Index n = static_cast<Index>(c.p.size());
  for (Index i = 0; i < n; ++i)
    for (Index j = i + 1; j < n; ++j)
      for (Index k = j + 1; k < n; ++k) {
        Tri t{i, j, k};
        double a = signed_area(c.p[i], c.p[j], c.p[k]);
        if (a < 0) {
          t = {i, k, j};
          a = -a;
        }
        const Vec2 o = circumcentre(c.p[i], c.p[j], c.p[k]);
        const double r2 = (c.p[i] - o).squaredNorm();
        bool empty = true;
        for (Index q = 0; q < n && empty; ++q) {
          if (q == i || q == j || q == k) continue;
          const double d2 = (c.p[q] - o).squaredNorm();
          EXPECT_GT(std::abs(d2 - r2), 1e-9 * r2) << "ambiguous (nearly cocircular) configuration";
          empty = d2 > r2;
        }
        if (!empty) continue;
        b.delaunay.insert(canonical(t));
        const double he = (c.h[i] + c.h[j] + c.h[k]) / 3.0;
        if (!(a > 0) || std::sqrt(r2) > alpha * he)
          ++b.removed_alpha;
        else if (all_boundary(c, t))
          ++b.removed_boundary;
        else
          b.kept.insert(canonical(t));
      }
  return b;
}

TEST(Remesh, RandomCloudMatchesBruteForceDelaunayAlphaTest) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0), hs(0.07, 0.12);
  Cloud c;
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    const double k = u(rng);
    c.add(u(rng), u(rng), k < 0.4 ? ParticleKind::Wall : (k < 0.5 ? ParticleKind::Ghost : ParticleKind::Fluid),
          hs(rng));
  }
  const double alpha = 1.2;
  const BruteForce b = brute_force(c, alpha);
  const RemeshResult r = c.mesh(alpha);

  EXPECT_EQ(canonical_set(delaunay_triangles(c.p)), b.delaunay);
  EXPECT_EQ(canonical_set(r.triangles), b.kept);
  EXPECT_EQ(r.triangles.size(), b.kept.size());
  EXPECT_EQ(r.removed_alpha, b.removed_alpha);
  EXPECT_EQ(r.removed_boundary_only, b.removed_boundary);
  // The cloud exercises every branch.
  EXPECT_GT(b.kept.size(), 50u);
  EXPECT_GT(b.removed_alpha, 10);
  EXPECT_GT(b.removed_boundary, 0);
  expect_ccw_and_alpha(c, r, alpha);

  double area = 0.0;
  std::vector<std::uint8_t> used(c.p.size(), 0);
  for (const Tri& t : b.kept) {
    area += heron_area(c.p[t[0]], c.p[t[1]], c.p[t[2]]);
    for (Index v : t) used[v] = 1;
  }
  EXPECT_NEAR(r.area, area, 1e-12 * area);
  EXPECT_EQ(r.connected, used);
  EXPECT_EQ(r.free_surface, free_surface_by_edge_count(c, r.triangles));
  int fs = 0;
  for (auto f : r.free_surface) fs += f;
  EXPECT_GT(fs, 10);
}

// ------------------------------------------------------------------------------------------------ (6)
TEST(Remesh, DuplicatePointsThrow) {
  Cloud c;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) c.add(i, j);
  EXPECT_NO_THROW(c.mesh());
  Cloud one = c;
  one.add(2, 3);
  try {
    one.mesh();
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("1 duplicate"), std::string::npos) << e.what();
  }
  Cloud two = one;
  two.add(0, 0, ParticleKind::Wall);
  try {
    two.mesh();
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2 duplicate"), std::string::npos) << e.what();
  }
  EXPECT_THROW(delaunay_triangles(one.p), std::invalid_argument);
  // Closer than 1e-12 of the bounding box (diagonal ~5.7): an error; 1e-9 apart: fine.
  Cloud near = c;
  near.add(2 + 1e-13, 3);
  EXPECT_THROW(near.mesh(), std::invalid_argument);
  EXPECT_THROW(delaunay_triangles(near.p), std::invalid_argument);
  Cloud apart = c;
  apart.add(2 + 1e-9, 3);
  EXPECT_NO_THROW(apart.mesh());
  // Collinear duplicates (dimension 1).
  EXPECT_THROW(remesh({Vec2(0, 0), Vec2(1, 0), Vec2(1, 0)}, std::vector<ParticleKind>(3), {1, 1, 1}, {}),
               std::invalid_argument);
  EXPECT_THROW(remesh({Vec2(0, 0), Vec2(1, 0), Vec2(1 + 1e-14, 0)}, std::vector<ParticleKind>(3), {1, 1, 1}, {}),
               std::invalid_argument);
}

TEST(Remesh, InvalidInputThrowsAndSmallInputIsEmpty) {
  Cloud c;
  c.add(0, 0);
  c.add(1, 0);
  c.add(0, 1);
  EXPECT_EQ(c.mesh().triangles.size(), 1u);
  auto bad = c;
  bad.h.pop_back();
  EXPECT_THROW(bad.mesh(), std::invalid_argument);
  bad = c;
  bad.kind.push_back(ParticleKind::Fluid);
  EXPECT_THROW(bad.mesh(), std::invalid_argument);
  bad = c;
  bad.p[1].y() = std::nan("");
  EXPECT_THROW(bad.mesh(), std::invalid_argument);
  bad = c;
  bad.p[2].x() = INFINITY;
  EXPECT_THROW(bad.mesh(), std::invalid_argument);
  bad = c;
  bad.h[0] = 0.0;
  EXPECT_THROW(bad.mesh(), std::invalid_argument);
  bad.h[0] = -1.0;
  EXPECT_THROW(bad.mesh(), std::invalid_argument);
  bad.h[0] = std::nan("");
  EXPECT_THROW(bad.mesh(), std::invalid_argument);
  EXPECT_THROW(c.mesh(0.0), std::invalid_argument);
  EXPECT_THROW(c.mesh(std::nan("")), std::invalid_argument);
  bad = c;
  bad.kind[0] = static_cast<ParticleKind>(7);
  EXPECT_THROW(bad.mesh(), std::invalid_argument);

  // Fewer than 3 points, or all collinear: no triangles, per-particle arrays sized, no error.
  const RemeshResult two = remesh({Vec2(0, 0), Vec2(1, 0)}, std::vector<ParticleKind>(2), {1, 1}, {});
  EXPECT_TRUE(two.triangles.empty());
  EXPECT_EQ(two.free_surface.size(), 2u);
  EXPECT_EQ(two.connected.size(), 2u);
  const RemeshResult none = remesh({}, {}, {}, {});
  EXPECT_TRUE(none.triangles.empty());
  const RemeshResult line =
      remesh({Vec2(0, 0), Vec2(1, 1), Vec2(2, 2), Vec2(3, 3)}, std::vector<ParticleKind>(4), {1, 1, 1, 1}, {});
  EXPECT_TRUE(line.triangles.empty());
  EXPECT_EQ(line.area, 0.0);
  EXPECT_EQ(line.connected, std::vector<std::uint8_t>(4, 0));
  EXPECT_TRUE(delaunay_triangles({Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)}).empty());
}

// ------------------------------------------------------------------------------------------------ (7)
TEST(Remesh, CloseFluidParticlesMatchesBruteForce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jit(-0.1, 0.1), ang(0.0, 2 * kPi);
  const int m = 20;
  Cloud c;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) c.add(i + jit(rng), j + jit(rng));
  // Planted fluid pairs, 0.2 h apart (the planted particle has the larger index).
  std::vector<Index> planted;
  for (int q : {45, 123, 207, 288, 351}) {
    const double th = ang(rng);
    planted.push_back(c.add(c.p[q].x() + 0.2 * std::cos(th), c.p[q].y() + 0.2 * std::sin(th)));
  }
  // A wall next to a fluid particle (larger index the fluid one), and a close wall-ghost pair.
  c.kind[66] = ParticleKind::Wall;
  c.add(c.p[66].x() + 0.15, c.p[66].y() + 0.05);
  c.kind[150] = ParticleKind::Wall;
  c.add(c.p[150].x() - 0.1, c.p[150].y() + 0.1, ParticleKind::Ghost);

  const RemeshResult r = c.mesh(1.3);
  const double fraction = 0.4;
  const std::vector<Index> got = close_fluid_particles(c.p, c.kind, c.h, r.triangles, fraction);

  std::set<Index> expected;
  for (std::size_t i = 0; i < c.p.size(); ++i)
    for (std::size_t j = i + 1; j < c.p.size(); ++j)
      if (c.kind[i] == ParticleKind::Fluid && c.kind[j] == ParticleKind::Fluid &&
          (c.p[i] - c.p[j]).norm() < fraction * 0.5 * (c.h[i] + c.h[j]))
        expected.insert(static_cast<Index>(j));
  EXPECT_EQ(expected, std::set<Index>(planted.begin(), planted.end()));
  EXPECT_EQ(std::set<Index>(got.begin(), got.end()), expected);
  EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
  EXPECT_EQ(got.size(), expected.size());  // each particle at most once
  for (Index i : got) EXPECT_EQ(c.kind[i], ParticleKind::Fluid);
  EXPECT_TRUE(close_fluid_particles(c.p, c.kind, c.h, r.triangles, 0.0).empty());

  // Three mutually close fluid particles: (a,b) closest -> b removed; (a,c) next -> c; (b,c) skipped.
  Cloud t = c;
  const Vec2 base(9.5, 9.5);
  const Index a = t.add(base.x(), base.y());
  const Index b = t.add(base.x() + 0.10, base.y());
  const Index cc = t.add(base.x() + 0.05, base.y() + 0.12);
  // A chain d - e - f with d-e and e-f close but d-f not: removing e resolves both pairs, f stays.
  const Vec2 base2(4.5, 14.5);
  const Index d = t.add(base2.x() - 0.3, base2.y());
  const Index e = t.add(base2.x(), base2.y());
  const Index f = t.add(base2.x() + 0.3, base2.y() + 0.05);
  ASSERT_LT((t.p[d] - t.p[e]).norm(), (t.p[e] - t.p[f]).norm());
  const RemeshResult rt = t.mesh(1.3);
  std::vector<Index> got3 = close_fluid_particles(t.p, t.kind, t.h, rt.triangles, fraction);
  std::vector<Index> expected3(planted.begin(), planted.end());
  expected3.push_back(b);
  expected3.push_back(cc);
  expected3.push_back(e);
  EXPECT_EQ(std::count(got3.begin(), got3.end(), d) + std::count(got3.begin(), got3.end(), f), 0);
  std::sort(expected3.begin(), expected3.end());
  EXPECT_EQ(got3, expected3);
  EXPECT_EQ(std::count(got3.begin(), got3.end(), a), 0);

  EXPECT_THROW(close_fluid_particles(c.p, c.kind, c.h, {{0, 1, static_cast<Index>(c.p.size())}}, 0.4),
               std::invalid_argument);
  EXPECT_THROW(close_fluid_particles(c.p, c.kind, {1.0}, r.triangles, 0.4), std::invalid_argument);
  EXPECT_THROW(close_fluid_particles(c.p, c.kind, c.h, r.triangles, -0.1), std::invalid_argument);
}

// ------------------------------------------------------------------------------------------------ (8)
TEST(Remesh, OversizedElementsMatchesBruteForce) {
  // Hand-made: area 2, h_e = 1.
  const std::vector<Vec2> p{Vec2(0, 0), Vec2(2, 0), Vec2(0, 2)};
  EXPECT_EQ(oversized_elements(p, {1, 1, 1}, {{0, 1, 2}}, 1.9), std::vector<Index>{0});
  EXPECT_TRUE(oversized_elements(p, {1, 1, 1}, {{0, 1, 2}}, 2.1).empty());
  EXPECT_EQ(oversized_elements(p, {0.5, 1, 1.5}, {{0, 2, 1}}, 1.9), std::vector<Index>{0});  // h_e = 1, CW

  // A perturbed grid with random holes, large alpha so that big elements are kept.
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> jit(-0.2, 0.2), u(0.0, 1.0);
  Cloud c;
  for (int j = 0; j < 25; ++j)
    for (int i = 0; i < 25; ++i)
      if (u(rng) > 0.2) c.add(i + jit(rng), j + jit(rng), ParticleKind::Fluid, 0.9 + 0.2 * u(rng));
  const RemeshResult r = c.mesh(2.5);
  const double factor = 0.8;
  std::vector<Index> expected;
  for (std::size_t e = 0; e < r.triangles.size(); ++e) {
    const Tri& t = r.triangles[e];
    const double he = (c.h[t[0]] + c.h[t[1]] + c.h[t[2]]) / 3.0;
    if (heron_area(c.p[t[0]], c.p[t[1]], c.p[t[2]]) > factor * he * he) expected.push_back(static_cast<Index>(e));
  }
  const std::vector<Index> got = oversized_elements(c.p, c.h, r.triangles, factor);
  EXPECT_EQ(got, expected);
  EXPECT_GT(got.size(), 10u);
  EXPECT_LT(got.size(), r.triangles.size() / 2);
  EXPECT_THROW(oversized_elements(c.p, c.h, {{0, 1, -1}}, factor), std::invalid_argument);
  EXPECT_THROW(oversized_elements(c.p, {1.0}, r.triangles, factor), std::invalid_argument);
}

}  // namespace
