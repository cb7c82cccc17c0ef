// What a structure (solid or shell body) offers to a coupling (interface.hpp), checked through the solid
// model itself: its wet boundary's points, the kinematics it reports for prescribed interface positions, and
// the positions it reports. The kinematics must be those of the time
// integrator's own update (v_{n+1}, a_{n+1} as functions of x_{n+1}) for Newmark and generalized-alpha alike;
// generalized-alpha's tangent coefficients belong to its intermediate evaluation point and would scale them.
#include <lagfsi/app/model_registry.hpp>
#include <lagfsi/case.hpp>
#include <lagfsi/interface.hpp>
#include <lagfsi/model.hpp>
#include <lagfsi/time_integrator.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <ostream>
#include <string>

namespace {

using namespace lagfsi;

CaseContext context(const Json& integrator, double dt) {
  CaseContext c;
  c.case_file = "test_structure_interface.json";
  c.base_dir = ".";
  c.out_dir = ".";
  c.analysis.type = "dynamic";
  c.analysis.dt = dt;
  c.analysis.end_time = 10 * dt;
  c.analysis.integrator = read_integrator(Params(integrator, "test", "/analysis/integrator"));
  c.analysis.linear_solver.type = "umfpack";
  return c;
}

Json body(const std::string& type) {
  if (type == "shell")
    return Json::parse(R"({"name": "wall", "type": "shell", "thickness": 0.02,
      "material": {"type": "svk", "young": 1e6, "density": 1000},
      "geometry": {"type": "line", "from": [0, 0], "to": [0, 1]}, "mesh": {"elements": 3, "order": 3},
      "boundary_conditions": [{"type": "fixed", "select": {"type": "point", "at": [0, 0]}}]})");
  return Json::parse(R"({"name": "wall", "type": "solid",
    "material": {"type": "svk", "young": 1e6, "density": 1000},
    "geometry": {"type": "rectangle", "origin": [0, 0], "size": [0.02, 1]},
    "mesh": {"type": "structured", "size": 0.02, "divisions": [1, 4], "order": 2},
    "boundary_conditions": [{"type": "fixed", "select": {"type": "segment", "from": [0, 0], "to": [0.02, 0]}}]})");
}

struct Config {
  std::string body;
  Json integrator;
};

void PrintTo(const Config& c, std::ostream* os) { *os << c.body << " with " << c.integrator.dump(); }

class StructureInterface : public ::testing::TestWithParam<Config> {};

TEST_P(StructureInterface, KinematicsAreTheIntegratorsUpdate) {
  // At rest at t = 0 (no loads: v_n = a_n = 0), every interface point prescribed at its start plus d: the
  // structure must report the velocity and acceleration its integrator's update gives a dof moved by d.
  const Config s = GetParam();
  const double dt = 0.01;
  const CaseContext ctx = context(s.integrator, dt);
  auto model = model_registry().at(s.body)(Params(body(s.body), "test.json", "/bodies/0"), ctx);
  auto* st = dynamic_cast<InterfaceStructure*>(model.get());
  ASSERT_NE(st, nullptr);
  const InterfaceBoundary ib = st->make_interface(Params(Json{{"type", "all"}}, "test.json", "/interface"));
  ASSERT_GT(ib.nodes.size(), 4u);
  model->initialize();
  model->predict(dt, dt);
  const Vec x0 = st->interface_positions_old(ib.nodes);
  const Vec2 d(1e-3, -2e-3);
  Vec x = x0;
  for (size_t k = 0; k < ib.nodes.size(); ++k) x.segment<2>(2 * k) += d;
  Vec v, a;
  st->interface_kinematics(ib.nodes, x, v, a);
  // The update of one 2-dof point from rest.
  std::unique_ptr<TimeIntegrator> ti =
      s.integrator["type"] == "newmark" ? make_newmark(0.25, 0.5) : make_generalized_alpha(s.integrator["rho_inf"]);
  KinematicState rest{0.0, Vec::Zero(2), Vec::Zero(2), Vec::Zero(2)}, out;
  ti->begin_step(rest, dt);
  ti->end_step(Vec(d), out);
  for (size_t k = 0; k < ib.nodes.size(); ++k) {
    EXPECT_LT((Vec2(v.segment<2>(2 * k)) - Vec2(out.v)).norm(), 1e-9 * out.v.norm()) << "point " << k;
    EXPECT_LT((Vec2(a.segment<2>(2 * k)) - Vec2(out.a)).norm(), 1e-9 * out.a.norm()) << "point " << k;
  }
  // From rest, the predictor has not moved the structure: its interface positions are still the start ones.
  EXPECT_LT((st->interface_positions(ib.nodes) - x0).norm(), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(BodiesAndIntegrators, StructureInterface,
                         ::testing::Values(Config{"solid", Json{{"type", "newmark"}, {"beta", 0.25}, {"gamma", 0.5}}},
                                           Config{"solid", Json{{"type", "generalized_alpha"}, {"rho_inf", 0.5}}},
                                           Config{"shell", Json{{"type", "newmark"}, {"beta", 0.25}, {"gamma", 0.5}}},
                                           Config{"shell", Json{{"type", "generalized_alpha"}, {"rho_inf", 0.5}}}),
                         [](const ::testing::TestParamInfo<Config>& i) {
                           return i.param.body + "_" +
                                  std::string(i.param.integrator["type"] == "newmark" ? "newmark"
                                                                                      : "generalized_alpha");
                         });

}  // namespace
