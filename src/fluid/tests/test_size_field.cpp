// Unit tests of the adaptive particle size field (src/fluid/size_field.hpp): the targets on a mesh grow from the
// sources by the gradation, stay within [h_min, h_max], are Lipschitz along every edge (the gradation limit), follow
// the refinement boxes inside their time windows, and bad input names its key. Expected values come from the
// formula h = min(h_max, h_min + g d) with d computed here from the lattice's geometry.
#include "size_field.hpp"

#include <lagfsi/error.hpp>
#include <lagfsi/meshing/primitives.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace {

using lagfsi::Index;
using lagfsi::InputError;
using lagfsi::Json;
using lagfsi::Params;
using lagfsi::Vec2;
using lagfsi::fluid::SizeField;

/// A fluid body's JSON with the given size_field (no other key is read by SizeField::read).
SizeField read_field(const Json& size_field, double h = 0.02) {
  Json body = {{"size_field", size_field}};
  SizeField::expand_shorthand(body);
  SizeField f;
  f.read(Params(body, "case.json", "/bodies/0"), h);
  return f;
}

struct Lattice {
  std::vector<Vec2> pts;
  std::vector<std::array<Index, 3>> tri;
};

/// The unit square as a structured (crossed) triangulation of n x n cells.
Lattice lattice(int n) {
  const lagfsi::TriMesh m = lagfsi::meshing::mesh_rectangle_structured(0, 0, 1, 1, n, n, "crossed");
  Lattice l;
  l.pts = m.nodes;
  for (size_t e = 0; e + 2 < m.conn.size(); e += 3) l.tri.push_back({m.conn[e], m.conn[e + 1], m.conn[e + 2]});
  return l;
}

TEST(SizeField, UniformByDefaultAndFromTheShorthand) {
  const SizeField none = read_field(Json{{"type", "uniform"}});
  EXPECT_FALSE(none.adaptive());
  const Lattice l = lattice(4);
  std::vector<double> h;
  none.targets(l.pts, l.tri, std::vector<char>(l.pts.size(), 0), 0.0, h);
  for (double s : h) EXPECT_EQ(s, 0.02);
  const SizeField on = read_field("adaptive");
  EXPECT_TRUE(on.adaptive());
  EXPECT_DOUBLE_EQ(on.h_max(), 4 * 0.02);
  EXPECT_DOUBLE_EQ(on.gradation(), 0.25);
}

TEST(SizeField, TargetsGrowWithTheDistanceFromTheSourcesUpToTheMaximum) {
  // Sources on the bottom row: every particle's size is h + g y, capped at max_size.
  const double h = 0.02, g = 0.25, hmax = 0.15;
  const SizeField f = read_field(Json{{"type", "adaptive"}, {"max_size", hmax}, {"gradation", g}}, h);
  const Lattice l = lattice(20);
  std::vector<char> source(l.pts.size(), 0);
  for (size_t i = 0; i < l.pts.size(); ++i) source[i] = l.pts[i].y() < 1e-12;
  std::vector<double> s;
  f.targets(l.pts, l.tri, source, 0.0, s);
  for (size_t i = 0; i < l.pts.size(); ++i) {
    const double expected = std::min(hmax, h + g * l.pts[i].y());
    EXPECT_NEAR(s[i], expected, 1e-12) << "particle at (" << l.pts[i].x() << ", " << l.pts[i].y() << ")";
  }
}

TEST(SizeField, TargetsAreGradedAlongEveryEdge) {
  // Sources at two corners: the size between two particles of an edge differs by at most g times the edge's length.
  const double g = 0.3;
  const SizeField f = read_field(Json{{"type", "adaptive"}, {"max_size", 1.0}, {"gradation", g}});
  const Lattice l = lattice(16);
  std::vector<char> source(l.pts.size(), 0);
  for (size_t i = 0; i < l.pts.size(); ++i)
    source[i] = (l.pts[i] - Vec2(0, 0)).norm() < 1e-12 || (l.pts[i] - Vec2(1, 1)).norm() < 1e-12;
  std::vector<double> s;
  f.targets(l.pts, l.tri, source, 0.0, s);
  for (const auto& t : l.tri)
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k], b = t[(k + 1) % 3];
      EXPECT_LE(std::abs(s[a] - s[b]), g * (l.pts[a] - l.pts[b]).norm() * (1 + 1e-9));
    }
  // The straight distance to the nearest corner, not a path's length along the lattice.
  for (size_t i = 0; i < l.pts.size(); ++i) {
    const double d = std::min(l.pts[i].norm(), (l.pts[i] - Vec2(1, 1)).norm());
    EXPECT_NEAR(s[i], 0.02 + g * d, 1e-12);
  }
}

TEST(SizeField, ABoxRefinesInsideItsTimeWindowAndParticlesOutOfTheMeshAreFine) {
  const Json box = {{"type", "box"}, {"min", {0.4, 0.4}}, {"max", {0.6, 0.6}},
                    {"size", 0.03},  {"from", 1.0},       {"to", 2.0}};
  const SizeField f =
      read_field(Json{{"type", "adaptive"}, {"max_size", 0.2}, {"gradation", 0.25}, {"regions", {box}}});
  Lattice l = lattice(10);
  l.pts.push_back(Vec2(5, 5));  // no element uses it
  const std::vector<char> none(l.pts.size(), 0);
  std::vector<double> during, before;
  f.targets(l.pts, l.tri, none, 1.5, during);
  f.targets(l.pts, l.tri, none, 0.5, before);
  for (size_t i = 0; i + 1 < l.pts.size(); ++i) {
    const Vec2& x = l.pts[i];
    const Vec2 out = (Vec2(0.4, 0.4) - x).cwiseMax(x - Vec2(0.6, 0.6)).cwiseMax(Vec2::Zero());
    EXPECT_NEAR(during[i], std::min(0.2, 0.03 + 0.25 * out.norm()), 1e-12);
    EXPECT_EQ(before[i], 0.2);
  }
  EXPECT_EQ(during.back(), 0.02);
  EXPECT_EQ(before.back(), 0.02);
}

TEST(SizeField, TheFlowIndicatorMarksAShearLayerAndNotARigidMotion) {
  // u = (U tanh((y - 1/2) / delta), 0): a shear layer of rate U / delta at y = 1/2 (gamma = |du/dy|), decaying
  // away from it; with the threshold at half the peak rate, the particles where the exact rate is well above it
  // are marked and those where it is well below are not; a rigid rotation (gamma = 0, though its gradient is larger
  // than the layer's) marks nothing.
  const double U = 1.0, delta = 0.05, peak = U / delta;
  const SizeField f = read_field(Json{{"type", "adaptive"}, {"strain_rate", 0.5 * peak}});
  EXPECT_DOUBLE_EQ(f.strain_rate(), 0.5 * peak);
  const Lattice l = lattice(40);
  std::vector<Vec2> shear(l.pts.size()), rotation(l.pts.size());
  for (size_t i = 0; i < l.pts.size(); ++i) {
    shear[i] = Vec2(U * std::tanh((l.pts[i].y() - 0.5) / delta), 0.0);
    rotation[i] = 30.0 * Vec2(-(l.pts[i].y() - 0.5), l.pts[i].x() - 0.5);
  }
  std::vector<char> source(l.pts.size(), 0);
  const Index marked = f.mark_straining(l.pts, shear, l.tri, source);
  EXPECT_GT(marked, 0);
  for (size_t i = 0; i < l.pts.size(); ++i) {
    const double rate = peak / std::pow(std::cosh((l.pts[i].y() - 0.5) / delta), 2);  // exact |du/dy|
    if (rate > 0.7 * peak) {
      EXPECT_TRUE(source[i]) << "y = " << l.pts[i].y();
    }
    if (rate < 0.3 * peak) {
      EXPECT_FALSE(source[i]) << "y = " << l.pts[i].y();
    }
  }
  std::vector<char> none(l.pts.size(), 0);
  EXPECT_EQ(f.mark_straining(l.pts, rotation, l.tri, none), 0);
  // Without a threshold (the default) nothing is marked.
  std::vector<char> off(l.pts.size(), 0);
  EXPECT_EQ(read_field("adaptive").mark_straining(l.pts, shear, l.tri, off), 0);
}

TEST(SizeField, BadInputNamesItsKey) {
  const auto error_of = [](const Json& j) {
    try {
      read_field(j);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of(Json{{"type", "adaptive"}, {"max_size", 0.01}}).find("/bodies/0/size_field/max_size"),
            std::string::npos);
  EXPECT_NE(error_of(Json{{"type", "adaptive"}, {"gradation", 1.5}}).find("/bodies/0/size_field/gradation"),
            std::string::npos);
  EXPECT_NE(error_of("graded").find("/bodies/0/size_field/type"), std::string::npos);
  EXPECT_NE(error_of(Json{{"type", "uniform"}, {"gradation", 0.2}}).find("/bodies/0/size_field/gradation"),
            std::string::npos);
  const Json inverted = {{"type", "box"}, {"min", {1, 1}}, {"max", {0, 0}}, {"size", 0.05}};
  EXPECT_NE(error_of(Json{{"type", "adaptive"}, {"regions", {inverted}}}).find("/bodies/0/size_field/regions/0/max"),
            std::string::npos);
  EXPECT_NE(error_of(Json{{"type", "adaptive"}, {"strain_rate", -1}}).find("/bodies/0/size_field/strain_rate"),
            std::string::npos);
  // A region's type may be left out (its default, "box"); another is refused.
  EXPECT_EQ(error_of(Json{{"type", "adaptive"}, {"regions", {{{"min", {0, 0}}, {"max", {1, 1}}, {"size", 0.05}}}}}),
            "no error");
  EXPECT_NE(error_of(Json{{"type", "adaptive"},
                          {"regions", {{{"type", "disc"}, {"min", {0, 0}}, {"max", {1, 1}}, {"size", 0.05}}}}})
                .find("/bodies/0/size_field/regions/0/type"),
            std::string::npos);
  const Json small = {{"type", "box"}, {"min", {0, 0}}, {"max", {1, 1}}, {"size", 0.001}};
  EXPECT_NE(error_of(Json{{"type", "adaptive"}, {"regions", {small}}}).find("/bodies/0/size_field/regions/0/size"),
            std::string::npos);
}

}  // namespace
