// Unit tests of the space partition and the parts' shares of the Delaunay triangulation (meshing/partition.hpp):
// every point in one part and the parts in proportion; the shares of 2, 3 and 5 parts together are the whole cloud's
// triangles with a circumradius within the halo, each once, for random points, a square lattice (every square's four
// points on one circle) and a jittered lattice with a hole; the ghosts are a layer, not the cloud. The parts' shares
// of the PFEM remeshing (remesh_part): together remesh()'s kept elements, free surface and counts, with the alpha
// test and with the advected detection flipping the previous mesh's edges back in.
#include <lagfsi/meshing/partition.hpp>
#include <lagfsi/meshing/previous_domain.hpp>
#include <lagfsi/meshing/remesh.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace {

using lagfsi::Index;
using lagfsi::Vec2;
using lagfsi::meshing::SpacePartition;
using Triangle = std::array<Index, 3>;

Triangle sorted(Triangle t) {
  std::sort(t.begin(), t.end());
  return t;
}

std::vector<Vec2> random_points(int n, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) p.emplace_back(2.0 * u(g), u(g));
  return p;
}

/// An n x m lattice of spacing h, jittered by `jitter` h, without the points in the disc (c, r).
std::vector<Vec2> lattice(int n, int m, double h, double jitter, Vec2 c = Vec2(-1, -1), double r = 0) {
  std::mt19937 g(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec2> p;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 x(i * h + jitter * h * u(g), j * h + jitter * h * u(g));
      if ((x - c).norm() >= r) p.push_back(x);
    }
  return p;
}

/// The shares of `parts` parts, together, against the whole triangulation's triangles with R <= halo.
void expect_shares_make_the_whole(const std::vector<Vec2>& pts, int parts, double halo) {
  std::set<Triangle> whole;
  for (const Triangle& t : lagfsi::meshing::delaunay_triangles(pts))
    if (lagfsi::meshing::circumcircle(pts, t).second <= halo) whole.insert(sorted(t));
  const SpacePartition partition(pts, parts);
  std::map<Triangle, int> seen;
  Index ghosts = 0;
  for (int k = 0; k < parts; ++k) {
    Index g = 0;
    for (const Triangle& t : lagfsi::meshing::part_delaunay(pts, partition, k, halo, &g)) ++seen[sorted(t)];
    ghosts += g;
  }
  std::size_t missing = 0, extra = 0, twice = 0;
  for (const Triangle& t : whole) missing += seen.count(t) == 0;
  for (const auto& [t, n] : seen) {
    extra += whole.count(t) == 0;
    twice += n > 1;
  }
  EXPECT_EQ(missing, 0u) << parts << " parts";
  EXPECT_EQ(extra, 0u) << parts << " parts";
  EXPECT_EQ(twice, 0u) << parts << " parts";
  EXPECT_EQ(seen.size(), whole.size());
  EXPECT_LT(ghosts, static_cast<Index>(pts.size()) / 2) << "the ghosts are a layer along the cuts";
}

TEST(SpacePartition, EveryPointIsInOnePartAndThePartsAreInProportion) {
  const std::vector<Vec2> pts = random_points(1000, 3);
  for (int parts : {1, 2, 3, 5, 8}) {
    const SpacePartition p(pts, parts);
    ASSERT_EQ(p.parts(), parts);
    std::vector<int> count(static_cast<size_t>(parts), 0);
    for (size_t i = 0; i < pts.size(); ++i) {
      const int k = p.owner()[i];
      ASSERT_GE(k, 0);
      ASSERT_LT(k, parts);
      EXPECT_EQ(p.part_of(pts[i]), k) << "point " << i;
      ++count[static_cast<size_t>(k)];
    }
    const auto [lo, hi] = std::minmax_element(count.begin(), count.end());
    EXPECT_LE(*hi - *lo, 2) << parts << " parts";
  }
  EXPECT_THROW(SpacePartition(pts, 0), std::invalid_argument);
}

TEST(PartDelaunay, TheSharesOfRandomPointsAreTheWholeTriangulation) {
  const std::vector<Vec2> pts = random_points(2000, 11);
  for (int parts : {2, 3, 5}) expect_shares_make_the_whole(pts, parts, 0.1);
}

TEST(PartDelaunay, TheSharesOfALatticeCutItsSquaresAsTheWholeDoes) {
  const std::vector<Vec2> pts = lattice(40, 25, 0.02, 0.0);
  for (int parts : {2, 3, 5}) expect_shares_make_the_whole(pts, parts, 1.2 * 0.02);
}

TEST(PartDelaunay, TheSharesOfAJitteredLatticeWithAHoleAreTheWholeTriangulation) {
  const std::vector<Vec2> pts = lattice(60, 30, 0.01, 0.2, Vec2(0.3, 0.15), 0.08);
  for (int parts : {2, 3, 5}) expect_shares_make_the_whole(pts, parts, 2.5 * 0.01);
}

using lagfsi::meshing::DomainDetection;
using lagfsi::meshing::ParticleKind;
using lagfsi::meshing::RemeshResult;
using lagfsi::meshing::RemeshSettings;

/// A dam-break-like scene: a jittered block of fluid particles (spacing h) with a hole, a few drops above it, on a
/// floor and against a left wall of wall particles.
struct Scene {
  std::vector<Vec2> points;
  std::vector<ParticleKind> kind;
  std::vector<double> h;
};

Scene scene(double h) {
  Scene s;
  for (const Vec2& p : lattice(50, 24, h, 0.2, Vec2(25 * h, 12 * h), 4 * h)) {
    s.points.push_back(p + Vec2(h, h));
    s.kind.push_back(ParticleKind::Fluid);
  }
  for (int k = 0; k < 6; ++k) {  // drops in flight
    s.points.push_back(Vec2((8 + 7 * k) * h, (29 + (k % 3)) * h));
    s.kind.push_back(ParticleKind::Fluid);
  }
  for (int i = 0; i < 60; ++i) {  // the floor, then the left wall
    s.points.push_back(Vec2(i * h, 0.0));
    s.kind.push_back(ParticleKind::Wall);
  }
  for (int j = 1; j < 35; ++j) {
    s.points.push_back(Vec2(0.0, j * h));
    s.kind.push_back(ParticleKind::Wall);
  }
  s.h.assign(s.points.size(), h);
  return s;
}

/// The parts' shares of remesh_part, put together: the elements (each counted), the flags or-ed, the counts summed.
struct Together {
  std::map<Triangle, int> elements;
  std::set<Triangle> added;
  std::vector<std::uint8_t> free_surface, connected;
  double area = 0;
  int restored = 0, lost = 0, kept_edges = 0;
};

Together put_together(const Scene& s, const RemeshSettings& settings, int parts, double halo) {
  const SpacePartition partition(s.points, parts);
  Together t;
  t.free_surface.assign(s.points.size(), 0);
  t.connected.assign(s.points.size(), 0);
  for (int k = 0; k < parts; ++k) {
    const RemeshResult r = lagfsi::meshing::remesh_part(s.points, s.kind, s.h, settings, partition, k, halo);
    for (const Triangle& e : r.triangles) ++t.elements[sorted(e)];
    for (Index e : r.added_elements) t.added.insert(sorted(r.triangles.at(static_cast<size_t>(e))));
    for (size_t i = 0; i < s.points.size(); ++i) {
      t.free_surface[i] |= r.free_surface[i];
      t.connected[i] |= r.connected[i];
    }
    t.area += r.area;
    t.restored += r.restored_edges;
    t.lost += r.lost_edges;
    t.kept_edges += r.kept_edges;
  }
  return t;
}

void expect_parts_make_the_remesh(const Scene& s, const RemeshSettings& settings, double halo) {
  const RemeshResult whole = lagfsi::meshing::remesh(s.points, s.kind, s.h, settings);
  std::set<Triangle> elements;
  for (const Triangle& e : whole.triangles) elements.insert(sorted(e));
  std::set<Triangle> added;
  for (Index e : whole.added_elements) added.insert(sorted(whole.triangles.at(static_cast<size_t>(e))));
  ASSERT_GT(elements.size(), 1000u);
  for (int parts : {1, 2, 3, 5}) {
    const Together t = put_together(s, settings, parts, halo);
    std::set<Triangle> together;
    int twice = 0;
    for (const auto& [e, n] : t.elements) {
      together.insert(e);
      twice += n > 1;
    }
    EXPECT_EQ(together, elements) << parts << " parts";
    EXPECT_EQ(twice, 0) << parts << " parts";
    EXPECT_EQ(t.added, added) << parts << " parts";
    EXPECT_EQ(t.free_surface, whole.free_surface) << parts << " parts";
    EXPECT_EQ(t.connected, whole.connected) << parts << " parts";
    EXPECT_NEAR(t.area, whole.area, 1e-12 * whole.area) << parts << " parts";
    EXPECT_EQ(t.restored, whole.restored_edges) << parts << " parts";
    EXPECT_EQ(t.lost, whole.lost_edges) << parts << " parts";
    EXPECT_EQ(t.kept_edges, whole.kept_edges) << parts << " parts";
  }
}

TEST(RemeshPart, ThePartsOfAnAlphaShapeRemeshingAreTheWholeOne) {
  const double h = 0.01;
  RemeshSettings settings;
  settings.alpha = 1.2;
  expect_parts_make_the_remesh(scene(h), settings, 2 * 1.2 * h + h);
}

TEST(RemeshPart, ThePartsOfAnAdvectedRemeshingFlipTheLastMeshsEdgesBackAsTheWholeOneDoes) {
  const double h = 0.01;
  Scene s = scene(h);
  RemeshSettings alpha;
  alpha.alpha = 1.2;
  const RemeshResult last = lagfsi::meshing::remesh(s.points, s.kind, s.h, alpha);
  // The particles move by up to 0.35 h: some of the last mesh's edges are no longer Delaunay.
  std::mt19937 g(5);
  std::uniform_real_distribution<double> u(-0.35 * h, 0.35 * h);
  for (size_t i = 0; i < s.points.size(); ++i)
    if (s.kind[i] == ParticleKind::Fluid) s.points[i] += Vec2(u(g), u(g));
  std::vector<std::array<Vec2, 3>> tris;
  std::set<std::pair<Index, Index>> edges;
  std::map<std::pair<Index, Index>, int> uses;
  for (const Triangle& e : last.triangles) {
    tris.push_back({s.points[static_cast<size_t>(e[0])], s.points[static_cast<size_t>(e[1])],
                    s.points[static_cast<size_t>(e[2])]});
    for (int k = 0; k < 3; ++k) {
      const auto key = std::minmax(e[k], e[(k + 1) % 3]);
      edges.insert(key);
      ++uses[key];
    }
  }
  std::vector<std::pair<Index, Index>> boundary;
  std::vector<std::array<Vec2, 2>> outline;
  for (const auto& [key, n] : uses)
    if (n == 1) {
      boundary.push_back(key);
      outline.push_back({s.points[static_cast<size_t>(key.first)], s.points[static_cast<size_t>(key.second)]});
    }
  lagfsi::meshing::PreviousDomain previous(std::move(tris), std::move(outline));
  previous.set_topology(last.connected, boundary);
  previous.set_edges({edges.begin(), edges.end()});
  RemeshSettings settings;
  settings.alpha = 1.2;
  settings.detection = DomainDetection::Advected;
  settings.previous = &previous;
  settings.separation_alpha = 2.5;
  settings.contact_gap = 0.3;
  settings.keep_edges_angle = 0.2;
  const RemeshResult whole = lagfsi::meshing::remesh(s.points, s.kind, s.h, settings);
  ASSERT_GT(whole.restored_edges + whole.kept_edges, 10) << "the test moves the particles enough to flip edges";
  expect_parts_make_the_remesh(s, settings, 2 * 2.5 * h + h);
}

TEST(RemeshPart, RefusesTheLevelSetDetectionAndAPartitionOfOtherPoints) {
  const Scene s = scene(0.01);
  RemeshSettings settings;
  const SpacePartition partition(s.points, 2);
  EXPECT_THROW(lagfsi::meshing::remesh_part(s.points, s.kind, s.h, settings, partition, 2, 0.05),
               std::invalid_argument);
  EXPECT_THROW(lagfsi::meshing::remesh_part(s.points, s.kind, s.h, settings, partition, 0, 0.0), std::invalid_argument);
  const std::vector<Vec2> fewer(s.points.begin(), s.points.end() - 1);
  const std::vector<ParticleKind> fewer_kind(s.kind.begin(), s.kind.end() - 1);
  const std::vector<double> fewer_h(s.h.begin(), s.h.end() - 1);
  EXPECT_THROW(lagfsi::meshing::remesh_part(fewer, fewer_kind, fewer_h, settings, partition, 0, 0.05),
               std::invalid_argument);
  lagfsi::meshing::PreviousDomain previous({{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}}, {});
  settings.detection = DomainDetection::LevelSet;
  settings.previous = &previous;
  settings.separation_alpha = 2.5;
  EXPECT_THROW(lagfsi::meshing::remesh_part(s.points, s.kind, s.h, settings, partition, 0, 0.05),
               std::invalid_argument);
}

}  // namespace
