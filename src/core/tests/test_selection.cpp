// Node selections (case.hpp, select_nodes): the nodes a polyline selects are those within its tolerance of one of
// its segments, and a polyline of fewer than two points is an input error naming the key.
#include <lagfsi/case.hpp>
#include <lagfsi/error.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using lagfsi::Index;
using lagfsi::Json;
using lagfsi::Params;
using lagfsi::Vec2;

std::vector<Index> select(const Json& j, const std::vector<Vec2>& nodes) {
  return lagfsi::select_nodes(Params(j, "case.json", "/s"), nodes);
}

TEST(Selection, APolylineSelectsTheNodesOnAnyOfItsSegmentsAndNoOthers) {
  // A flag's outline clamped on an arc: the three wet faces (lower, end, upper) are selected; the arc's node,
  // a node on the chord that would close the polyline (it is open), a node 0.7 mm off the lower face and a
  // node beyond the polyline's last point are not.
  const std::vector<Vec2> nodes = {{0.249, 0.19}, {0.4, 0.19}, {0.6, 0.19},  {0.6, 0.2},    {0.6, 0.21}, {0.4, 0.21},
                                   {0.249, 0.21}, {0.25, 0.2}, {0.249, 0.2}, {0.4, 0.1893}, {0.1, 0.21}};
  const Json line = {{"type", "polyline"}, {"points", {{0.249, 0.19}, {0.6, 0.19}, {0.6, 0.21}, {0.249, 0.21}}}};
  EXPECT_EQ(select(line, nodes), (std::vector<Index>{0, 1, 2, 3, 4, 5, 6}));
  // A tolerance of 0.9 mm takes the node 0.7 mm off the lower face too, and still not the arc's (1 mm off the chord).
  Json wide = line;
  wide["tolerance"] = 0.9e-3;
  EXPECT_EQ(select(wide, nodes), (std::vector<Index>{0, 1, 2, 3, 4, 5, 6, 9}));
}

TEST(Selection, APolylineOfOnePointIsAnErrorNamingTheKey) {
  try {
    select({{"type", "polyline"}, {"points", {{0.0, 0.0}}}}, {{0.0, 0.0}});
    FAIL() << "no error";
  } catch (const lagfsi::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/s/points"), std::string::npos) << e.what();
  }
}

}  // namespace
