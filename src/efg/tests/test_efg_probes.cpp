// EFG displacement probe (the path-following tables 5.1-5.2 of the INSANE EFG thesis): "value": "parameter" reads the
// MLS nodal parameter v of a node, "value": "displacement" (the default) the displacement u = sum_j N_j(x_k) v_j. On
// a small cantilever (rho = 3h, bilinear basis, linear elastic, one load step) the displacement of an interior
// particle equals that sum with the shape functions computed here independently by MlsShape, and differs from its
// parameter; at an active FE node (the coupled clamped edge) v = u exactly, as the thesis states.
#include <lagfsi/case.hpp>
#include <lagfsi/efg/efg_model.hpp>
#include <lagfsi/efg/mls.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace lagfsi;

namespace {

/// 4 x 2 cantilever, 8 x 4 cells (h = 0.5), the end x = 0 held in y and at its two corners in x (coupling), an
/// upward shear on x = 4; one load step of lambda = 1.
struct Cantilever {
  CaseContext ctx;
  std::unique_ptr<efg::EfgModel> m;
  Cantilever() {
    Json body = {
        {"name", "beam"},
        {"type", "efg"},
        {"domain", {{"type", "rectangle"}, {"size", {4.0, 2.0}}, {"divisions", {8, 4}}}},
        {"material", {{"type", "linear_elastic"}, {"young", 1000.0}, {"poisson", 0.3}}},
        {"efg", {{"basis", "bilinear"}, {"alpha", 3.0}, {"gauss", 4}}},
        {"boundary_conditions",
         {{{"type", "fixed"}, {"select", {{"type", "segment"}, {"from", {0, 0}}, {"to", {0, 2}}}}, {"components", "y"}},
          {{"type", "fixed"}, {"select", {{"type", "point"}, {"at", {0, 0}}}}, {"components", "x"}},
          {{"type", "fixed"}, {"select", {{"type", "point"}, {"at", {0, 2}}}}, {"components", "x"}}}},
        {"loads",
         {{{"type", "traction"},
           {"select", {{"type", "segment"}, {"from", {4, 0}}, {"to", {4, 2}}}},
           {"value", {0, 1.0}}}}}};
    ctx.analysis.type = "static";
    ctx.analysis.dt = 1.0;
    ctx.analysis.end_time = 1.0;
    ctx.analysis.linear_solver.type = "cholmod";
    ctx.analysis.newton.residual_tolerance = 1e-12;
    m = std::make_unique<efg::EfgModel>(Params(body, "beam.json", "/bodies/0"), ctx);
    m->initialize();
    m->predict(1.0, 1.0);
    for (int it = 0; it < 5; ++it)
      if (m->solve_iteration().converged) break;
    m->finalize_step();
  }
  double probe(const Json& at, const std::string& comp, const std::string& value) {
    Json p = {{"name", "p"}, {"type", "displacement"}, {"body", "beam"},
              {"at", at},    {"component", comp},      {"value", value}};
    return m->make_probe(Params(p, "beam.json", "/probes/0"))->sample().at(0);
  }
  Index node_at(const Vec2& x) const {
    const auto& nodes = m->mesh().nodes;
    for (Index n = 0; n < static_cast<Index>(nodes.size()); ++n)
      if ((nodes[n] - x).norm() < 1e-9) return n;
    return -1;
  }
};

}  // namespace

TEST(EfgProbes, ParticleDisplacementIsTheMlsSumOfTheParameters) {
  Cantilever c;
  const Vec2 xb(3.0, 1.0);  // interior particle, far from the coupling cells at x = 0
  const Index b = c.node_at(xb);
  ASSERT_GE(b, 0);
  const Vec& v = c.m->parameters();
  const double vb = c.probe({3.0, 1.0}, "y", "parameter"), ub = c.probe({3.0, 1.0}, "y", "displacement");
  EXPECT_EQ(vb, v[2 * b + 1]);
  // u_B from the MLS functions at x_B computed here: rho = 3h = 1.5 at every node of the regular grid.
  efg::InfluenceDomain dom;
  efg::MlsShape mls(efg::Basis{efg::BasisType::bilinear}, dom);
  const auto& nodes = c.m->mesh().nodes;
  std::vector<Vec2> rho(nodes.size(), Vec2::Constant(1.5));
  std::vector<Index> all(nodes.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
  efg::ShapeValues sh;
  mls.compute(xb, nodes, rho, all, sh, nullptr, "test", false);
  double u = 0;
  for (size_t k = 0; k < sh.nodes.size(); ++k) u += sh.N[k] * v[2 * sh.nodes[k] + 1];
  std::printf("node B (3, 1): v_y %.10e, u_y %.10e (independent MLS sum %.10e), v/u %.6f, support %zu\n", vb, ub, u,
              vb / ub, sh.nodes.size());
  EXPECT_NEAR(ub, u, 1e-12 * std::abs(u));
  EXPECT_GT(std::abs(ub), 0.0);
  EXPECT_GT(std::abs(vb - ub), 1e-4 * std::abs(ub));  // a particle: the MLS does not interpolate
  EXPECT_NEAR(ub, c.m->nodal_displacements()[2 * b + 1], 1e-12 * std::abs(ub));
}

TEST(EfgProbes, ActiveNodeParameterIsItsDisplacement) {
  Cantilever c;
  const double v = c.probe({0.0, 0.5}, "x", "parameter"), u = c.probe({0.0, 0.5}, "x", "displacement");
  std::printf("active node (0, 0.5): v_x %.10e, u_x %.10e\n", v, u);
  EXPECT_GT(std::abs(u), 1e-6);  // free in x (held in y only): not a trivial zero
  EXPECT_NEAR(u, v, 1e-12 * std::abs(u));
}
