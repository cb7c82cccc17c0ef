// Unit tests of lagfsi::meshing (mesh_polygon, mesh_rectangle_structured, elevate, arc_points) and of
// boundary_edges on elevated meshes. Expected values are computed independently of the mesher
// (shoelace areas, explicit barycentric positions, edge sets rebuilt from the connectivity).
#include <lagfsi/geometry2d.hpp>
#include <lagfsi/mesh.hpp>
#include <lagfsi/meshing/primitives.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {

using lagfsi::BoundaryEdge;
using lagfsi::cross;
using lagfsi::Index;
using lagfsi::TriMesh;
using lagfsi::Vec2;
using lagfsi::meshing::PolygonRegion;

constexpr double kPi = std::numbers::pi;

// Signed area of the straight triangle of element e's vertices.
double element_area(const TriMesh& m, Index e) {
  const Index* c = m.element(e);
  return 0.5 * cross(m.nodes[c[1]] - m.nodes[c[0]], m.nodes[c[2]] - m.nodes[c[0]]);
}

double total_area(const TriMesh& m) {
  double a = 0.0;
  for (Index e = 0; e < m.num_elements(); ++e) a += element_area(m, e);
  return a;
}

double polygon_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * std::abs(a);
}

double polygon_perimeter(const std::vector<Vec2>& p) {
  double l = 0.0;
  for (size_t i = 0; i < p.size(); ++i) l += (p[(i + 1) % p.size()] - p[i]).norm();
  return l;
}

// Minimum interior angle (degrees) over all elements.
double min_angle_deg(const TriMesh& m) {
  double amin = 180.0;
  for (Index e = 0; e < m.num_elements(); ++e) {
    const Index* c = m.element(e);
    for (int k = 0; k < 3; ++k) {
      const Vec2 u = m.nodes[c[(k + 1) % 3]] - m.nodes[c[k]];
      const Vec2 v = m.nodes[c[(k + 2) % 3]] - m.nodes[c[k]];
      amin = std::min(amin, std::acos(std::clamp(u.dot(v) / (u.norm() * v.norm()), -1.0, 1.0)) * 180.0 / kPi);
    }
  }
  return amin;
}

double max_edge(const TriMesh& m) {
  double l = 0.0;
  for (Index e = 0; e < m.num_elements(); ++e) {
    const Index* c = m.element(e);
    for (int k = 0; k < 3; ++k) l = std::max(l, (m.nodes[c[(k + 1) % 3]] - m.nodes[c[k]]).norm());
  }
  return l;
}

std::pair<Index, Index> ordered(Index a, Index b) { return {std::min(a, b), std::max(a, b)}; }

std::set<std::pair<Index, Index>> unique_edges(const TriMesh& m) {
  std::set<std::pair<Index, Index>> edges;
  for (Index e = 0; e < m.num_elements(); ++e) {
    const Index* c = m.element(e);
    for (int k = 0; k < 3; ++k) edges.insert(ordered(c[k], c[(k + 1) % 3]));
  }
  return edges;
}

std::vector<Vec2> rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// Basic validity: every element counter-clockwise with positive area, every node used, node indices
// in range, no two nodes at the same position.
void expect_valid(const TriMesh& m) {
  ASSERT_EQ(m.conn.size() % m.nodes_per_element(), 0u);
  std::vector<int> used(m.nodes.size(), 0);
  for (Index v : m.conn) {
    ASSERT_GE(v, 0);
    ASSERT_LT(v, m.num_nodes());
    used[v] = 1;
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << "unused nodes";
  for (Index e = 0; e < m.num_elements(); ++e) EXPECT_GT(element_area(m, e), 0.0) << "element " << e;
  std::vector<std::pair<double, double>> pts;
  for (const Vec2& p : m.nodes) pts.emplace_back(p.x(), p.y());
  std::sort(pts.begin(), pts.end());
  EXPECT_EQ(std::adjacent_find(pts.begin(), pts.end()), pts.end()) << "duplicate node coordinates";
}

// Total length of the boundary (sum over the order+1 nodes of each boundary edge) and check that the
// boundary is closed: each boundary vertex starts exactly one edge and ends exactly one edge.
double boundary_length_closed(const TriMesh& m) {
  const auto edges = lagfsi::boundary_edges(m);
  std::map<Index, int> starts, ends;
  double len = 0.0;
  for (const BoundaryEdge& be : edges) {
    EXPECT_EQ(be.nodes.size(), static_cast<size_t>(m.order + 1));
    starts[be.nodes.front()] += 1;
    ends[be.nodes.back()] += 1;
    for (size_t i = 0; i + 1 < be.nodes.size(); ++i) len += (m.nodes[be.nodes[i + 1]] - m.nodes[be.nodes[i]]).norm();
  }
  EXPECT_EQ(starts.size(), edges.size());
  EXPECT_EQ(ends.size(), edges.size());
  for (const auto& [v, n] : starts) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(ends.count(v), 1u) << "boundary not closed at node " << v;
  }
  return len;
}

// ------------------------------------------------------------------------------------ mesh_polygon

TEST(MeshPolygon, RectangleAreaQualityAndBoundarySpacing) {
  // Side lengths not multiples of h: 1.0 -> 7 pieces of 1/7, 0.7 -> 5 pieces of 0.14.
  const double h = 0.15, w = 1.0, ht = 0.7;
  const TriMesh m = lagfsi::meshing::mesh_polygon({rect(0.0, 0.0, w, ht), {}}, h);
  ASSERT_EQ(m.order, 1);
  expect_valid(m);
  EXPECT_NEAR(total_area(m), w * ht, 1e-12 * w * ht);
  EXPECT_LE(max_edge(m), 1.5 * h);
  EXPECT_GE(min_angle_deg(m), 20.0);
  // Boundary: closed, on the rectangle, edges of the even spacing of their side.
  const auto bnd = lagfsi::boundary_edges(m);
  EXPECT_EQ(bnd.size(), 2u * (7 + 5));
  for (const BoundaryEdge& be : bnd) {
    const Vec2 a = m.nodes[be.nodes[0]], b = m.nodes[be.nodes[1]];
    const bool horizontal = a.y() == b.y();
    const bool vertical = a.x() == b.x();
    ASSERT_TRUE(horizontal || vertical) << "boundary edge not on a side";
    if (horizontal) {
      EXPECT_TRUE(a.y() == 0.0 || a.y() == ht);
      EXPECT_NEAR((b - a).norm(), w / 7, 1e-12);
    } else {
      EXPECT_TRUE(a.x() == 0.0 || a.x() == w);
      EXPECT_NEAR((b - a).norm(), ht / 5, 1e-12);
    }
  }
  EXPECT_NEAR(boundary_length_closed(m), 2 * (w + ht), 1e-12);
}

TEST(MeshPolygon, ExactMultipleOfH) {
  // 2 / 0.1 is 20.000000000000004 in floating point: still 20 boundary pieces per long side.
  const TriMesh m = lagfsi::meshing::mesh_polygon({rect(0.0, 0.0, 2.0, 1.0), {}}, 0.1);
  expect_valid(m);
  EXPECT_EQ(lagfsi::boundary_edges(m).size(), 2u * (20 + 10));
  EXPECT_NEAR(total_area(m), 2.0, 2e-12);
  EXPECT_GE(min_angle_deg(m), 20.0);
  // The size bound h caps the edge length: the mean edge is about 0.7 h, so there are about twice
  // as many elements as equilateral triangles of side h would need (area / (0.43 h^2)).
  EXPECT_GT(m.num_elements(), 1.0 * 2.0 / (0.43 * 0.01));
  EXPECT_LT(m.num_elements(), 3.0 * 2.0 / (0.43 * 0.01));
}

TEST(MeshPolygon, ThinPartsKeepQuality) {
  // Parts much thinner than h: the boundary must be split further to keep the minimum angle.
  const TriMesh thin = lagfsi::meshing::mesh_polygon({rect(0, 0, 1, 0.01), {}}, 0.1);
  expect_valid(thin);
  EXPECT_NEAR(total_area(thin), 0.01, 1e-14);
  EXPECT_GE(min_angle_deg(thin), 20.0);
  // A hole 0.01 away from the outer loop.
  const TriMesh gap = lagfsi::meshing::mesh_polygon({rect(0, 0, 1, 1), {rect(0.2, 0.2, 0.8, 0.99)}}, 0.1);
  expect_valid(gap);
  EXPECT_NEAR(total_area(gap), 1.0 - 0.6 * 0.79, 1e-12);
  EXPECT_GE(min_angle_deg(gap), 20.0);
  EXPECT_LE(max_edge(gap), 1.5 * 0.1);
  EXPECT_NEAR(boundary_length_closed(gap), 4.0 + 2 * (0.6 + 0.79), 1e-12);
}

TEST(MeshPolygon, ClockwiseOuterLoop) {
  auto loop = rect(-1.0, 2.0, 0.5, 3.0);
  std::reverse(loop.begin(), loop.end());
  const TriMesh m = lagfsi::meshing::mesh_polygon({loop, {}}, 0.2);
  expect_valid(m);
  EXPECT_NEAR(total_area(m), 1.5, 1.5e-12);
  for (const Vec2& p : m.nodes) {
    EXPECT_GE(p.x(), -1.0);
    EXPECT_LE(p.x(), 0.5);
    EXPECT_GE(p.y(), 2.0);
    EXPECT_LE(p.y(), 3.0);
  }
}

TEST(MeshPolygon, AGradedSizeGivesEdgesThatFollowIt) {
  // A size that grows from h at the bottom edge by g per unit height: every element's longest edge is below the size
  // at its centroid (1.5 times it in the second pass), the elements well above the bottom are several times larger
  // than those along it (the boundary itself is split at h everywhere), and the mesh has far fewer elements than the
  // uniform one at h.
  const double h = 0.02, g = 0.25;
  const auto size = [&](const Vec2& x) { return h + g * x.y(); };
  const TriMesh graded = lagfsi::meshing::mesh_polygon({rect(0.0, 0.0, 1.0, 1.0), {}}, h, 5e6, size);
  const TriMesh uniform = lagfsi::meshing::mesh_polygon({rect(0.0, 0.0, 1.0, 1.0), {}}, h);
  expect_valid(graded);
  EXPECT_NEAR(total_area(graded), 1.0, 1e-12);
  EXPECT_GE(min_angle_deg(graded), 20.0);
  double bottom = 0, top = 0;
  int n_bottom = 0, n_top = 0;
  for (Index e = 0; e < graded.num_elements(); ++e) {
    const Index* c = graded.element(e);
    const Vec2 a = graded.nodes[c[0]], b = graded.nodes[c[1]], d = graded.nodes[c[2]];
    const double longest = std::max({(a - b).norm(), (b - d).norm(), (d - a).norm()});
    const Vec2 centroid = (a + b + d) / 3.0;
    EXPECT_LE(longest, 1.5 * size(centroid) * (1 + 1e-9)) << "element " << e;
    if (centroid.y() < 0.05) bottom += longest, ++n_bottom;
    if (centroid.y() > 0.6 && centroid.y() < 0.8) top += longest, ++n_top;
  }
  ASSERT_GT(n_bottom, 0);
  ASSERT_GT(n_top, 0);
  EXPECT_GT(top / n_top, 3.0 * bottom / n_bottom);
  EXPECT_LT(graded.num_elements(), uniform.num_elements() / 4);
}

TEST(MeshPolygon, LShape) {
  const std::vector<Vec2> L{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const double h = 0.1;
  const TriMesh m = lagfsi::meshing::mesh_polygon({L, {}}, h);
  expect_valid(m);
  EXPECT_NEAR(total_area(m), 3.0, 3e-12);
  EXPECT_GE(min_angle_deg(m), 20.0);
  EXPECT_LE(max_edge(m), 1.5 * h);
  // No element in the notch [1,2] x [1,2].
  for (Index e = 0; e < m.num_elements(); ++e) {
    const Index* c = m.element(e);
    const Vec2 g = (m.nodes[c[0]] + m.nodes[c[1]] + m.nodes[c[2]]) / 3.0;
    EXPECT_FALSE(g.x() > 1.0 && g.y() > 1.0) << "element " << e << " in the notch";
  }
  EXPECT_NEAR(boundary_length_closed(m), 8.0, 1e-12);
}

TEST(MeshPolygon, SquareHole) {
  // Hole given clockwise, off-centre.
  auto hole = rect(0.3, 0.4, 0.6, 0.7);
  std::reverse(hole.begin(), hole.end());
  const double h = 0.05;
  const TriMesh m = lagfsi::meshing::mesh_polygon({rect(0, 0, 1, 1), {hole}}, h);
  expect_valid(m);
  EXPECT_NEAR(total_area(m), 1.0 - 0.09, 1e-12);
  EXPECT_GE(min_angle_deg(m), 20.0);
  EXPECT_LE(max_edge(m), 1.5 * h);
  for (Index e = 0; e < m.num_elements(); ++e) {
    const Index* c = m.element(e);
    const Vec2 g = (m.nodes[c[0]] + m.nodes[c[1]] + m.nodes[c[2]]) / 3.0;
    EXPECT_FALSE(g.x() > 0.3 && g.x() < 0.6 && g.y() > 0.4 && g.y() < 0.7) << "element " << e << " in the hole";
  }
  EXPECT_NEAR(boundary_length_closed(m), 4.0 + 1.2, 1e-12);
}

TEST(MeshPolygon, CircularHoleAndTwoHoles) {
  const double h = 0.04;
  auto circle = lagfsi::meshing::arc_points({0.5, 0.5}, 0.2, 0.0, 2 * kPi, h);
  circle.pop_back();  // closed loop: the last point repeats the first
  const TriMesh m = lagfsi::meshing::mesh_polygon({rect(0, 0, 2, 1), {circle}}, h);
  expect_valid(m);
  const double expected = 2.0 - polygon_area(circle);
  EXPECT_NEAR(total_area(m), expected, 1e-12 * expected);
  EXPECT_GE(min_angle_deg(m), 20.0);
  EXPECT_NEAR(boundary_length_closed(m), 6.0 + polygon_perimeter(circle), 1e-12);

  // Second hole, a triangle, counter-clockwise.
  const std::vector<Vec2> tri{{1.2, 0.2}, {1.8, 0.3}, {1.5, 0.8}};
  const TriMesh m2 = lagfsi::meshing::mesh_polygon({rect(0, 0, 2, 1), {circle, tri}}, h);
  expect_valid(m2);
  const double expected2 = expected - polygon_area(tri);
  EXPECT_NEAR(total_area(m2), expected2, 1e-12 * expected2);
  EXPECT_NEAR(boundary_length_closed(m2), 6.0 + polygon_perimeter(circle) + polygon_perimeter(tri), 1e-12);
}

TEST(MeshPolygon, DegenerateInputsThrow) {
  using lagfsi::meshing::mesh_polygon;
  const auto sq = rect(0, 0, 1, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(mesh_polygon({{{0, 0}, {1, 0}}, {}}, 0.1), std::invalid_argument);                  // < 3 points
  EXPECT_THROW(mesh_polygon({{{0, 0}, {1, 0}, {2, 0}}, {}}, 0.1), std::invalid_argument);          // collinear
  EXPECT_THROW(mesh_polygon({{{0, 0}, {1, 1}, {1, 0}, {0, 1}}, {}}, 0.1), std::invalid_argument);  // bow-tie
  EXPECT_THROW(mesh_polygon({{{0, 0}, {1, 0}, {1, 1}, {1, 1}, {0, 1}}, {}}, 0.1),
               std::invalid_argument);                                                             // repeated point
  EXPECT_THROW(mesh_polygon({{{0, 0}, {2, 0}, {1, 0}, {1, 1}}, {}}, 0.1), std::invalid_argument);  // backtracking
  EXPECT_THROW(mesh_polygon({{{0, 0}, {1, 0}, {1, nan}, {0, 1}}, {}}, 0.1), std::invalid_argument);
  EXPECT_THROW(mesh_polygon({sq, {}}, 0.0), std::invalid_argument);
  EXPECT_THROW(mesh_polygon({sq, {}}, -0.1), std::invalid_argument);
  EXPECT_THROW(mesh_polygon({sq, {}}, nan), std::invalid_argument);
  EXPECT_THROW(mesh_polygon({sq, {}}, inf), std::invalid_argument);
  EXPECT_THROW(mesh_polygon({sq, {}}, 1e-4), std::invalid_argument);  // ~2.3e8 elements expected
  // Holes: crossing the outer loop, outside it, touching it, nested, degenerate.
  EXPECT_THROW(mesh_polygon({sq, {rect(0.5, 0.5, 1.5, 0.8)}}, 0.1), std::invalid_argument);
  EXPECT_THROW(mesh_polygon({sq, {rect(2, 2, 3, 3)}}, 0.1), std::invalid_argument);
  EXPECT_THROW(mesh_polygon({sq, {rect(0.5, 0.5, 1.0, 0.8)}}, 0.1), std::invalid_argument);
  EXPECT_THROW(mesh_polygon({sq, {rect(0.2, 0.2, 0.8, 0.8), rect(0.4, 0.4, 0.6, 0.6)}}, 0.1), std::invalid_argument);
  EXPECT_THROW(mesh_polygon({sq, {{{0.2, 0.2}, {0.4, 0.4}, {0.6, 0.6}}}}, 0.1), std::invalid_argument);
  // A valid region still works after these.
  EXPECT_NO_THROW(mesh_polygon({sq, {rect(0.4, 0.4, 0.6, 0.6)}}, 0.1));
}

TEST(MeshPolygon, HundredThousandElements) {
  // About 2.1 area / (0.43 h^2) elements (see ExactMultipleOfH): h = 0.007 gives about 1e5.
  const double h = 0.007;
  const TriMesh m = lagfsi::meshing::mesh_polygon({rect(0, 0, 1, 1), {}}, h);
  EXPECT_GT(m.num_elements(), 70000);
  EXPECT_LT(m.num_elements(), 150000);
  EXPECT_LE(max_edge(m), 1.5 * h);
  EXPECT_NEAR(total_area(m), 1.0, 1e-11);
  EXPECT_GE(min_angle_deg(m), 20.0);
}

// -------------------------------------------------------------------------------- structured mesh

TEST(MeshRectangleStructured, CountsPositionsAndAreas) {
  const double x0 = -1.0, y0 = 0.5, x1 = 2.0, y1 = 1.5;
  const int nx = 6, ny = 4;
  for (const char* pattern : {"right", "left", "crossed"}) {
    SCOPED_TRACE(pattern);
    const TriMesh m = lagfsi::meshing::mesh_rectangle_structured(x0, y0, x1, y1, nx, ny, pattern);
    ASSERT_EQ(m.order, 1);
    ASSERT_EQ(m.num_nodes(), (nx + 1) * (ny + 1));
    ASSERT_EQ(m.num_elements(), 2 * nx * ny);
    expect_valid(m);
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const Vec2& p = m.nodes[j * (nx + 1) + i];
        EXPECT_NEAR(p.x(), x0 + (x1 - x0) * i / nx, 1e-14);
        EXPECT_NEAR(p.y(), y0 + (y1 - y0) * j / ny, 1e-14);
      }
    EXPECT_EQ(m.nodes[(nx + 1) * (ny + 1) - 1], Vec2(x1, y1));  // exact corner
    const double cell = (x1 - x0) / nx * (y1 - y0) / ny;
    for (Index e = 0; e < m.num_elements(); ++e) EXPECT_NEAR(element_area(m, e), 0.5 * cell, 1e-14);
    EXPECT_NEAR(total_area(m), (x1 - x0) * (y1 - y0), 1e-13);
    EXPECT_EQ(unique_edges(m).size(), static_cast<size_t>(nx * (ny + 1) + ny * (nx + 1) + nx * ny));
    EXPECT_NEAR(boundary_length_closed(m), 2 * (x1 - x0 + y1 - y0), 1e-13);
  }
}

TEST(MeshRectangleStructured, Diagonals) {
  const int nx = 4, ny = 2;
  auto id = [&](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
  for (const char* pattern : {"right", "left", "crossed"}) {
    SCOPED_TRACE(pattern);
    const auto edges = unique_edges(lagfsi::meshing::mesh_rectangle_structured(0, 0, 1, 1, nx, ny, pattern));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const bool rising = std::string(pattern) == "right" || (std::string(pattern) == "crossed" && (i + j) % 2 == 0);
        const auto diag = rising ? ordered(id(i, j), id(i + 1, j + 1)) : ordered(id(i + 1, j), id(i, j + 1));
        const auto other = rising ? ordered(id(i + 1, j), id(i, j + 1)) : ordered(id(i, j), id(i + 1, j + 1));
        EXPECT_EQ(edges.count(diag), 1u) << "cell " << i << "," << j;
        EXPECT_EQ(edges.count(other), 0u) << "cell " << i << "," << j;
      }
  }
}

TEST(MeshRectangleStructured, CrossedIsMirrorSymmetric) {
  // With even nx and ny the crossed pattern is symmetric about both mid-lines of the rectangle.
  const TriMesh m = lagfsi::meshing::mesh_rectangle_structured(0, 0, 4, 2, 4, 2, "crossed");
  auto triangles = [&](bool mx, bool my) {
    std::set<std::array<std::pair<double, double>, 3>> out;
    for (Index e = 0; e < m.num_elements(); ++e) {
      std::array<std::pair<double, double>, 3> t;
      for (int k = 0; k < 3; ++k) {
        const Vec2& p = m.nodes[m.element(e)[k]];
        t[k] = {mx ? 4.0 - p.x() : p.x(), my ? 2.0 - p.y() : p.y()};
      }
      std::sort(t.begin(), t.end());
      out.insert(t);
    }
    return out;
  };
  const auto ref = triangles(false, false);
  EXPECT_EQ(triangles(true, false), ref);
  EXPECT_EQ(triangles(false, true), ref);
}

TEST(MeshRectangleStructured, BadArgumentsThrow) {
  using lagfsi::meshing::mesh_rectangle_structured;
  EXPECT_THROW(mesh_rectangle_structured(0, 0, 1, 1, 0, 1), std::invalid_argument);
  EXPECT_THROW(mesh_rectangle_structured(0, 0, 1, 1, 1, -2), std::invalid_argument);
  EXPECT_THROW(mesh_rectangle_structured(1, 0, 1, 1, 1, 1), std::invalid_argument);
  EXPECT_THROW(mesh_rectangle_structured(0, 1, 1, 0, 1, 1), std::invalid_argument);
  EXPECT_THROW(mesh_rectangle_structured(0, 0, std::numeric_limits<double>::quiet_NaN(), 1, 1, 1),
               std::invalid_argument);
  EXPECT_THROW(mesh_rectangle_structured(0, 0, 1, 1, 2, 2, "diagonal"), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------- elevate

// Barycentric coordinates (of vertices 0, 1, 2) of the nodes of T6 and T10, as documented in mesh.hpp.
std::vector<std::array<double, 3>> parent_coordinates(int order) {
  const double t = 1.0 / 3.0;
  if (order == 2) return {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
  return {{1, 0, 0},     {0, 1, 0},     {0, 0, 1}, {2 * t, t, 0}, {t, 2 * t, 0},  // edge 0-1 from vertex 0
          {0, 2 * t, t}, {0, t, 2 * t},                                           // edge 1-2 from vertex 1
          {t, 0, 2 * t}, {2 * t, 0, t},                                           // edge 2-0 from vertex 2
          {t, t, t}};
}

void check_elevated(const TriMesh& lin, int order) {
  SCOPED_TRACE("order " + std::to_string(order));
  const TriMesh m = lagfsi::meshing::elevate(lin, order);
  ASSERT_EQ(m.order, order);
  ASSERT_EQ(m.num_elements(), lin.num_elements());
  const size_t V = lin.nodes.size(), E = unique_edges(lin).size(), T = static_cast<size_t>(lin.num_elements());
  EXPECT_EQ(m.nodes.size(), V + (order - 1) * E + (order == 3 ? T : 0));
  expect_valid(m);  // includes: no two nodes at the same position (shared edge nodes are shared)
  // Vertices unchanged.
  for (size_t i = 0; i < V; ++i) EXPECT_EQ(m.nodes[i], lin.nodes[i]);
  const auto L = parent_coordinates(order);
  ASSERT_EQ(L.size(), static_cast<size_t>(m.nodes_per_element()));
  for (Index e = 0; e < m.num_elements(); ++e) {
    const Index* c = m.element(e);
    const Index* cl = lin.element(e);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(c[k], cl[k]);
    const Vec2 &x0 = lin.nodes[cl[0]], &x1 = lin.nodes[cl[1]], &x2 = lin.nodes[cl[2]];
    const double scale = (x1 - x0).norm() + (x2 - x0).norm();
    for (int k = 3; k < m.nodes_per_element(); ++k) {
      const Vec2 expected = L[k][0] * x0 + L[k][1] * x1 + L[k][2] * x2;
      EXPECT_LT((m.nodes[c[k]] - expected).norm(), 1e-14 * scale) << "element " << e << " node " << k;
    }
  }
  // Each interior edge: its two elements use the same high-order nodes, in opposite order.
  std::map<std::pair<Index, Index>, std::vector<Index>> seen;  // directed edge -> inner nodes
  for (Index e = 0; e < m.num_elements(); ++e) {
    const Index* c = m.element(e);
    for (int k = 0; k < 3; ++k) {
      std::vector<Index> inner;
      for (int i = 0; i < order - 1; ++i) inner.push_back(c[3 + k * (order - 1) + i]);
      seen[{c[k], c[(k + 1) % 3]}] = inner;
    }
  }
  size_t interior = 0;
  for (const auto& [edge, inner] : seen) {
    auto it = seen.find({edge.second, edge.first});
    if (it == seen.end()) continue;
    ++interior;
    std::vector<Index> reversed(it->second.rbegin(), it->second.rend());
    EXPECT_EQ(inner, reversed);
  }
  EXPECT_GT(interior, 0u);
  // Boundary: same edges as the linear mesh, closed, straight.
  EXPECT_EQ(lagfsi::boundary_edges(m).size(), lagfsi::boundary_edges(lin).size());
  EXPECT_NEAR(boundary_length_closed(m), boundary_length_closed(lin), 1e-12);
}

TEST(Elevate, StructuredAndUnstructured) {
  const TriMesh s = lagfsi::meshing::mesh_rectangle_structured(0, 0, 2, 1, 5, 3, "crossed");
  auto hole = lagfsi::meshing::arc_points({1.0, 0.5}, 0.25, 0.0, 2 * kPi, 0.1);
  hole.pop_back();
  const TriMesh u = lagfsi::meshing::mesh_polygon({rect(0, 0, 2, 1), {hole}}, 0.1);
  for (const TriMesh* lin : {&s, &u})
    for (int order : {2, 3}) check_elevated(*lin, order);
}

TEST(Elevate, T10BoundaryPerimeterAndOrientation) {
  const std::vector<Vec2> L{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const TriMesh m = lagfsi::meshing::elevate(lagfsi::meshing::mesh_polygon({L, {}}, 0.25), 3);
  EXPECT_NEAR(boundary_length_closed(m), 8.0, 1e-12);
  for (const BoundaryEdge& be : lagfsi::boundary_edges(m)) {
    ASSERT_EQ(be.nodes.size(), 4u);
    const Vec2 a = m.nodes[be.nodes[0]], b = m.nodes[be.nodes[3]];
    EXPECT_LT((m.nodes[be.nodes[1]] - (a + (b - a) / 3.0)).norm(), 1e-14);
    EXPECT_LT((m.nodes[be.nodes[2]] - (a + 2.0 * (b - a) / 3.0)).norm(), 1e-14);
    // Counter-clockwise outer boundary: the domain (the element's third vertex) is on the left.
    const Index* c = m.element(be.element);
    const Vec2 third = m.nodes[c[(be.local_edge + 2) % 3]];
    EXPECT_GT(cross(b - a, third - a), 0.0);
  }
}

TEST(Elevate, TwoTrianglesByHand) {
  // Square (0,0),(1,0),(1,1),(0,1) split by the diagonal 0-2; the diagonal is 0->2 in element 0 and
  // 2->0 in element 1.
  TriMesh lin;
  lin.nodes = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  lin.conn = {0, 1, 2, 2, 3, 0};
  const TriMesh m = lagfsi::meshing::elevate(lin, 3);
  ASSERT_EQ(m.nodes.size(), 4u + 2 * 5 + 2);
  const Index* a = m.element(0);
  const Index* b = m.element(1);
  // Element 0, local edge 2 runs 2 -> 0: nodes at (2/3, 2/3) then (1/3, 1/3).
  EXPECT_LT((m.nodes[a[7]] - Vec2(2.0 / 3, 2.0 / 3)).norm(), 1e-15);
  EXPECT_LT((m.nodes[a[8]] - Vec2(1.0 / 3, 1.0 / 3)).norm(), 1e-15);
  // Element 1 is (2, 3, 0): its local edge 2 runs from c[2] = 0 to c[0] = 2, nodes at (1/3, 1/3)
  // then (2/3, 2/3): the same nodes as element 0's, in the opposite order.
  EXPECT_EQ(b[7], a[8]);
  EXPECT_EQ(b[8], a[7]);
  EXPECT_LT((m.nodes[b[9]] - Vec2(1.0 / 3, 2.0 / 3)).norm(), 1e-15);
  const TriMesh q = lagfsi::meshing::elevate(lin, 2);
  ASSERT_EQ(q.nodes.size(), 4u + 5);
  EXPECT_EQ(q.element(0)[5], q.element(1)[5]);
  EXPECT_LT((q.nodes[q.element(0)[5]] - Vec2(0.5, 0.5)).norm(), 1e-15);
}

TEST(Elevate, OrderOneAndBadArguments) {
  const TriMesh lin = lagfsi::meshing::mesh_rectangle_structured(0, 0, 1, 1, 2, 2);
  const TriMesh same = lagfsi::meshing::elevate(lin, 1);
  EXPECT_EQ(same.order, 1);
  EXPECT_EQ(same.conn, lin.conn);
  EXPECT_EQ(same.nodes, lin.nodes);
  EXPECT_THROW(lagfsi::meshing::elevate(lin, 0), std::invalid_argument);
  EXPECT_THROW(lagfsi::meshing::elevate(lin, 4), std::invalid_argument);
  EXPECT_THROW(lagfsi::meshing::elevate(lagfsi::meshing::elevate(lin, 2), 3), std::invalid_argument);
}

// ------------------------------------------------------------------------------------- arc_points

TEST(ArcPoints, EndPointsSpacingAndDirection) {
  const Vec2 c(1.0, -2.0);
  const double r = 0.5, h = 0.07;
  const auto p = lagfsi::meshing::arc_points(c, r, 0.25, 2.0, h);
  const size_t n = static_cast<size_t>(std::ceil(1.75 * r / h));
  ASSERT_EQ(p.size(), n + 1);
  EXPECT_LT((p.front() - (c + r * Vec2(std::cos(0.25), std::sin(0.25)))).norm(), 1e-15);
  EXPECT_LT((p.back() - (c + r * Vec2(std::cos(2.0), std::sin(2.0)))).norm(), 1e-15);
  for (size_t i = 0; i < p.size(); ++i) {
    EXPECT_NEAR((p[i] - c).norm(), r, 1e-15);
    if (i + 1 < p.size()) {
      EXPECT_LE((p[i + 1] - p[i]).norm(), h);
      EXPECT_NEAR((p[i + 1] - p[i]).norm(), (p[1] - p[0]).norm(), 1e-14);  // uniform
      EXPECT_GT(cross(p[i] - c, p[i + 1] - c), 0.0);                       // counter-clockwise
    }
  }
  const auto q = lagfsi::meshing::arc_points(c, r, kPi, 0.0, 0.1);  // clockwise
  for (size_t i = 0; i + 1 < q.size(); ++i) EXPECT_LT(cross(q[i] - c, q[i + 1] - c), 0.0);
  EXPECT_THROW(lagfsi::meshing::arc_points(c, 0.0, 0.0, 1.0, 0.1), std::invalid_argument);
  EXPECT_THROW(lagfsi::meshing::arc_points(c, 1.0, 0.0, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(lagfsi::meshing::arc_points(c, 1.0, 0.0, std::numeric_limits<double>::infinity(), 0.1),
               std::invalid_argument);
}

}  // namespace
