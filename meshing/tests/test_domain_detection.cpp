// Unit tests of the conservative PFEM domain detections (meshing/previous_domain.hpp, remesh.hpp
// DomainDetection) on hand-made clouds whose expected domains are known in closed form: an L-shaped lattice
// (its notch is a concave corner the alpha shape fills with a large alpha), two blocks a gap apart (merged
// only when the gap closes, or once it is below contact_gap), a dent of one surface (never filled), a dry wall
// particle (wetted only by fluid that reaches it), and water against a wall (its flat element kept).
#include <lagfsi/meshing/previous_domain.hpp>
#include <lagfsi/meshing/remesh.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <utility>
#include <vector>

namespace {

using lagfsi::Index;
using lagfsi::Vec2;
using lagfsi::meshing::DomainDetection;
using lagfsi::meshing::ParticleKind;
using lagfsi::meshing::PreviousDomain;
using lagfsi::meshing::remesh;
using lagfsi::meshing::RemeshSettings;

struct Cloud {
  std::vector<Vec2> p;
  std::vector<ParticleKind> kind;
  std::vector<double> h;
  void add(double x, double y, ParticleKind k = ParticleKind::Fluid) {
    p.emplace_back(x, y);
    kind.push_back(k);
    h.push_back(1.0);
  }
};

/// The unit squares [i, i+1] x [j, j+1] with `cell(i, j)` true, as two triangles each.
template <class Cell>
PreviousDomain squares(int nx, int ny, Cell cell) {
  std::vector<std::array<Vec2, 3>> tris;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (cell(i, j)) {
        const Vec2 a(i, j), b(i + 1, j), c(i + 1, j + 1), d(i, j + 1);
        tris.push_back({a, b, c});
        tris.push_back({a, c, d});
      }
  return PreviousDomain(std::move(tris), {});
}

double kept_area(const Cloud& c, const RemeshSettings& s) { return remesh(c.p, c.kind, c.h, s).area; }

TEST(PreviousDomain, LocatesPointsAndMeasuresTheBoundaryDistance) {
  // The unit square as two triangles, its four sides as the boundary.
  const Vec2 a(0, 0), b(1, 0), c(1, 1), d(0, 1);
  PreviousDomain dom({{a, b, c}, {a, c, d}}, {{a, b}, {b, c}, {c, d}, {d, a}});
  EXPECT_TRUE(dom.contains(Vec2(0.5, 0.5)));
  EXPECT_TRUE(dom.contains(Vec2(0.25, 0.75)));
  EXPECT_TRUE(dom.contains(Vec2(1.0, 0.5))) << "the border counts as inside";
  EXPECT_FALSE(dom.contains(Vec2(1.01, 0.5)));
  EXPECT_FALSE(dom.contains(Vec2(-3.0, 7.0)));
  EXPECT_NEAR(dom.boundary_distance(Vec2(0.5, 0.4), 1.0), 0.4, 1e-14);
  EXPECT_NEAR(dom.boundary_distance(Vec2(1.3, 1.4), 1.0), 0.5, 1e-14) << "to the corner (1, 1)";
  EXPECT_DOUBLE_EQ(dom.boundary_distance(Vec2(5.0, 5.0), 0.25), 0.25) << "capped at the limit";
  EXPECT_NEAR(dom.area(), 1.0, 1e-15);
}

TEST(DomainDetection, AdvectedKeepsTheConcaveCornerOfAnLShapeThatTheAlphaShapeFills) {
  // Lattice points of an L: [0,4]x[0,2] plus [0,2]x[2,4] (area 12). The alpha shape (alpha = 1.2) also takes
  // the element (2,2)-(3,2)-(2,3) in the concave corner (circumradius 0.71): area 12.5. The advected
  // predicate keeps the L: that element has two edges on the previous boundary (a dent, not a contact).
  Cloud c;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i)
      if (j <= 2 || i <= 2) c.add(i, j);
  const auto in_l = [](int i, int j) { return j < 2 || i < 2; };
  PreviousDomain prev = squares(4, 4, in_l);
  // Its boundary edges (unit lattice edges with the L on one side only), in the cloud's numbering.
  const auto index = [&](int i, int j) {
    for (Index k = 0; k < static_cast<Index>(c.p.size()); ++k)
      if (c.p[k] == Vec2(i, j)) return k;
    return Index(-1);
  };
  const auto cell = [&](int i, int j) { return i >= 0 && j >= 0 && i < 4 && j < 4 && in_l(i, j); };
  std::vector<std::pair<Index, Index>> boundary;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) {
      if (i < 4 && cell(i, j) != cell(i, j - 1)) boundary.emplace_back(index(i, j), index(i + 1, j));
      if (j < 4 && cell(i, j) != cell(i - 1, j)) boundary.emplace_back(index(i, j), index(i, j + 1));
    }
  ASSERT_EQ(boundary.size(), 16u);
  prev.set_topology({}, boundary);
  RemeshSettings alpha;
  alpha.alpha = 1.2;
  EXPECT_NEAR(kept_area(c, alpha), 12.5, 1e-12);
  RemeshSettings adv = alpha;
  adv.detection = DomainDetection::Advected;
  adv.previous = &prev;
  EXPECT_NEAR(kept_area(c, adv), 12.0, 1e-12);
  RemeshSettings ls = adv;
  ls.detection = DomainDetection::LevelSet;
  ls.level_set_band = 0.1;  // the corner element's centroid is 1/3 from the L
  EXPECT_NEAR(kept_area(c, ls), 12.0, 1e-12);
}

/// Two 2x2 lattice blocks, the second shifted by `gap` in x, remeshed with the advected detection whose
/// previous domain is the two blocks (contact_gap as given).
lagfsi::meshing::RemeshResult two_blocks(double gap, double contact_gap = 0.0) {
  Cloud c;
  std::vector<std::array<Vec2, 3>> tris;
  for (int b = 0; b < 2; ++b) {
    const double x0 = b * (2.0 + gap);
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 2; ++i) c.add(x0 + i, j);
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const Vec2 a(x0 + i, j), bb(x0 + i + 1, j), cc(x0 + i + 1, j + 1), d(x0 + i, j + 1);
        tris.push_back({a, bb, cc});
        tris.push_back({a, cc, d});
      }
  }
  const PreviousDomain prev(std::move(tris), {});
  RemeshSettings s;
  s.alpha = 1.2;
  s.detection = DomainDetection::Advected;
  s.previous = &prev;
  s.contact_gap = contact_gap;
  return remesh(c.p, c.kind, c.h, s);
}

TEST(DomainDetection, TwoBlocksMergeOnlyWhenTheGapCloses) {
  const auto apart = two_blocks(3.0);  // gap elements of circumradius >= 1.58: not added
  EXPECT_NEAR(apart.area, 8.0, 1e-12);
  EXPECT_EQ(apart.added_outside, 0);
  const auto touching = two_blocks(0.6);  // gap 0.6: elements of circumradius ~0.58 close it
  EXPECT_NEAR(touching.area, 8.0 + 2 * 0.6, 1e-12);
  EXPECT_GT(touching.added_outside, 0);
}

TEST(DomainDetection, ContactGapJoinsSurfacesOnlyOnceTheirGapHasNearlyClosed) {
  // The gap elements between the blocks' facing columns have the smallest height gap / sqrt(1 + gap^2): 0.51
  // at gap 0.6 (the alpha test takes them, adding 1.2 of area no particle brought), 0.24 at gap 0.25.
  const auto wide = two_blocks(0.6, 0.3);
  EXPECT_NEAR(wide.area, 8.0, 1e-12) << "a gap of 0.6 h is not closed with contact_gap = 0.3";
  EXPECT_EQ(wide.added_outside, 0);
  const auto narrow = two_blocks(0.25, 0.3);
  EXPECT_NEAR(narrow.area, 8.0 + 2 * 0.25, 1e-12) << "a gap of 0.25 h is";
  EXPECT_EQ(narrow.added_outside, 4);
  EXPECT_NEAR(two_blocks(0.6, 0.6).area, 8.0 + 2 * 0.6, 1e-12) << "and 0.6 h with contact_gap = 0.6";
}

TEST(DomainDetection, ADentOfOneSurfaceIsNotFilledAndADryWallIsWettedOnlyByFluidThatReachesIt) {
  // A flat row of surface particles y = 1 over a row y = 0, the middle one sunk to y = 0.45: the element over
  // the dent (its two edges on the previous boundary) passes alpha = 1.2 but is not added.
  Cloud c;
  for (int i = 0; i <= 4; ++i) c.add(i, 0);
  for (int i = 0; i <= 4; ++i) c.add(i, i == 2 ? 0.45 : 1.0);  // the dent's element: R = 1.184
  std::vector<std::array<Vec2, 3>> tris;
  for (int i = 0; i < 4; ++i) {
    const Vec2 a(i, 0), b(i + 1, 0), cc = c.p[5 + i + 1], d = c.p[5 + i];
    tris.push_back({a, b, cc});
    tris.push_back({a, cc, d});
  }
  PreviousDomain prev(tris, {});
  std::vector<std::pair<Index, Index>> surface;
  for (Index i = 5; i < 9; ++i) surface.emplace_back(i, i + 1);
  prev.set_topology({}, surface);
  RemeshSettings s;
  s.alpha = 1.2;
  s.detection = DomainDetection::Advected;
  s.previous = &prev;
  const double area = prev.area();
  EXPECT_NEAR(kept_area(c, s), area, 1e-12);
  // A dry wall particle 0.8 above the surface particle (4, 1) with a fluid neighbour at (3, 1): it joins only
  // once a fluid particle comes within wetting_distance h of it.
  c.add(4.0, 1.8, lagfsi::meshing::ParticleKind::Wall);
  std::vector<std::uint8_t> meshed(c.p.size() - 1, 1);
  meshed.push_back(0);  // the dry wall particle
  prev.set_topology(meshed, surface);
  s.wetting_distance = 0.5;
  EXPECT_NEAR(kept_area(c, s), area, 1e-12) << "0.8 h away: stays dry";
  s.wetting_distance = 1.0;
  const double wetted = kept_area(c, s);
  EXPECT_GT(wetted, area + 0.1) << "within h: wetted";
  s.contact_gap = 0.3;
  EXPECT_NEAR(kept_area(c, s), wetted, 1e-12) << "contact_gap is for two fluid surfaces, not for a wall";
}

}  // namespace

namespace {

TEST(DomainDetection, AdvectedRestoresAnOldBoundaryEdgeThatIsNoLongerDelaunay) {
  // The previous domain is the triangle a (0,0), b (1,0), e (0.5,-0.8) (area 0.4), its top edge a-b on the free
  // surface. Inside it is d (0.5,-0.2); outside, c (0.5,0.05) just above the edge. a-b is not Delaunay in the new
  // cloud (c lies in the circle through a, b, d): Delaunay has c-d instead, and the two faces across a-b, (b,c,d)
  // and (c,a,d), straddle the old surface with centroids inside it. Without the restored edge both are kept and
  // the domain gains the part of them above a-b (area 0.425); with it, (a,d,b) is kept and (a,b,c) is an outside
  // face that the alpha test (h = 0.04) rejects: the area stays 0.4.
  Cloud c;
  for (const auto& [x, y] :
       std::vector<std::pair<double, double>>{{0, 0}, {1, 0}, {0.5, -0.8}, {0.5, -0.2}, {0.5, 0.05}})
    c.add(x, y);
  for (double& h : c.h) h = 0.04;
  const Vec2 a(0, 0), b(1, 0), e(0.5, -0.8);
  PreviousDomain prev({{a, b, e}}, {{a, b}, {b, e}, {e, a}});
  prev.set_topology({1, 1, 1, 1, 0}, {{0, 1}, {1, 2}, {0, 2}});
  RemeshSettings s;
  s.alpha = 1.2;
  s.detection = DomainDetection::Advected;
  s.previous = &prev;
  s.separation_alpha = 100.0;
  const auto r = remesh(c.p, c.kind, c.h, s);
  EXPECT_EQ(r.restored_edges, 1);
  EXPECT_EQ(r.lost_edges, 0);
  EXPECT_NEAR(r.area, 0.4, 1e-12);
  EXPECT_EQ(r.triangles.size(), 3u);
}

/// True if some triangle has the edge (a, b).
bool has_edge(const std::vector<std::array<Index, 3>>& tri, Index a, Index b) {
  for (const auto& t : tri)
    for (int k = 0; k < 3; ++k)
      if ((t[k] == a && t[(k + 1) % 3] == b) || (t[k] == b && t[(k + 1) % 3] == a)) return true;
  return false;
}

TEST(DomainDetection, KeepsAPreviousInteriorEdgeWithinTheFlipHysteresis) {
  // A unit square whose previous mesh had the diagonal 0-2; corner 1 has moved inwards to (0.97, 0.03), so the
  // angles facing 0-2 sum to 183.5 degrees and Delaunay takes 1-3. With keep_edges_angle 10 degrees the old
  // diagonal is flipped back; with 2 degrees, or without the previous edges, it is not. The area is the
  // quadrilateral's either way.
  Cloud c;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0, 0}, {0.97, 0.03}, {1, 1}, {0, 1}}) c.add(x, y);
  const Vec2 p0(0, 0), p1(0.97, 0.03), p2(1, 1), p3(0, 1);
  const auto run = [&](double degrees, bool with_edges) {
    PreviousDomain prev({{p0, p1, p2}, {p0, p2, p3}}, {{p0, p1}, {p1, p2}, {p2, p3}, {p3, p0}});
    prev.set_topology({1, 1, 1, 1}, {{0, 1}, {1, 2}, {2, 3}, {0, 3}});
    if (with_edges) prev.set_edges({{0, 1}, {1, 2}, {2, 3}, {0, 3}, {0, 2}});
    RemeshSettings s;
    s.alpha = 1.2;
    s.detection = DomainDetection::Advected;
    s.previous = &prev;
    s.separation_alpha = 100.0;
    s.keep_edges_angle = degrees * std::numbers::pi / 180.0;
    return remesh(c.p, c.kind, c.h, s);
  };
  const auto kept = run(10.0, true);
  EXPECT_EQ(kept.kept_edges, 1);
  EXPECT_TRUE(has_edge(kept.triangles, 0, 2));
  EXPECT_FALSE(has_edge(kept.triangles, 1, 3));
  const double quad = 0.5 * (0.97 * 1.0 - 0.03 * 1.0) + 0.5 * 1.0;  // (0,1,2) + (0,2,3)
  EXPECT_NEAR(kept.area, quad, 1e-12);
  for (const auto& r : {run(2.0, true), run(10.0, false), run(0.0, true)}) {
    EXPECT_EQ(r.kept_edges, 0);
    EXPECT_TRUE(has_edge(r.triangles, 1, 3));
    EXPECT_NEAR(r.area, quad, 1e-12);
  }
}

TEST(DomainDetection, WaterAgainstAWallDoesNotSeparateFromIt) {
  // Walls as constraints: particles 0 and 1 lie on the floor y = 0, spread 1.9 h apart by a flow along it, and the
  // water's particle 2 has come within 0.17 h of the floor between them. Their flat element (circumradius 2.74 h)
  // fails the separation test (2.5 h): without the floor's particles marked, it is cut out and particle 2 becomes a
  // free surface inside the water. Marked on the wall, the element leans on the floor and is kept; it is cut out
  // when particle 2 was on the previous free surface (a boundary edge of it with no end on a wall: a film).
  Cloud c;
  for (const auto& [x, y] :
       std::vector<std::pair<double, double>>{{0, 0}, {1.9, 0}, {0.95, 0.17}, {0, 1.2}, {1.9, 1.2}, {0.95, 1.2}})
    c.add(x, y);
  const Vec2 lo(0, 0), hi(1.9, 1.2);
  const std::vector<std::uint8_t> on_wall{1, 1, 0, 0, 0, 0};
  const double box = 1.9 * 1.2, sliver = 0.5 * 1.9 * 0.17;
  std::function<bool(const Vec2&)> along;  // empty: every edge between two marked particles runs along a wall
  const auto run = [&](bool marked, std::vector<std::pair<Index, Index>> boundary) {
    PreviousDomain prev({{lo, Vec2(1.9, 0), hi}, {lo, hi, Vec2(0, 1.2)}}, {});
    prev.set_topology({1, 1, 1, 1, 1, 1}, std::move(boundary));
    RemeshSettings s;
    s.alpha = 1.2;
    s.detection = DomainDetection::Advected;
    s.previous = &prev;
    s.separation_alpha = 2.5;
    if (marked) s.on_wall = &on_wall;
    s.along_wall = along;
    return remesh(c.p, c.kind, c.h, s);
  };
  const std::vector<std::pair<Index, Index>> walls_and_top{{0, 1}, {1, 4}, {4, 5}, {5, 3}, {3, 0}};
  const auto unmarked = run(false, walls_and_top);
  EXPECT_EQ(unmarked.separated_inside, 1);
  EXPECT_NEAR(unmarked.area, box - sliver, 1e-12);
  EXPECT_EQ(unmarked.free_surface[2], 1);
  const auto marked = run(true, walls_and_top);
  EXPECT_EQ(marked.separated_inside, 0);
  EXPECT_NEAR(marked.area, box, 1e-12);
  EXPECT_EQ(marked.free_surface[2], 0);
  const auto film = run(true, {{0, 1}, {2, 5}, {1, 4}, {4, 5}, {5, 3}, {3, 0}});
  EXPECT_EQ(film.separated_inside, 1);
  EXPECT_NEAR(film.area, box - sliver, 1e-12);
  // The edge must run along a wall (its midpoint on a wall's line): between particles on two walls that meet at a
  // corner it crosses the water, and the element is tested as any other.
  along = [](const Vec2& p) { return std::abs(p.y()) < 1e-12; };
  EXPECT_EQ(run(true, walls_and_top).separated_inside, 0);
  along = [](const Vec2& p) { return std::abs(p.x()) < 1e-12 || std::abs(p.x() - 1.9) < 1e-12; };
  EXPECT_EQ(run(true, walls_and_top).separated_inside, 1);
}

}  // namespace
