// The fluid's named presets of defaults ("preset", src/fluid/fluid_input.cpp; docs/fluid_settings.md): `lagfsi
// check` prints the preset a fluid body resolves to and the defaults it gives the derived keys — conservative for
// the monolithic scheme with remeshing, classic for the fractional step — a preset chosen in the case gives its
// family to either scheme, a key given in the case overrides its preset's value, and the conservative preset with
// a fixed mesh is refused naming the key.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "case_runner.hpp"

namespace {

using namespace lagfsi::testing;

/// The resolved first body of a tank whose fluid body has the extra keys `body` and the scheme `scheme`.
struct Checked {
  int exit_code = -1;
  std::string stderr_text;
  nlohmann::json body;
};

Checked check_tank(const nlohmann::json& body, const nlohmann::json& scheme, const std::string& tag) {
  nlohmann::json j = nlohmann::json::parse(R"({
    "name": "tank", "analysis": {"type": "dynamic", "dt": 0.01, "end_time": 0.1}, "gravity": [0, -9.81],
    "bodies": [{"name": "water", "type": "fluid", "density": 1000.0, "viscosity": 1e-3, "spacing": 0.05,
                "regions": [{"type": "rectangle", "origin": [0, 0], "size": [0.5, 0.25]}],
                "walls": [{"name": "tank", "points": [[0, 0.5], [0, 0], [1, 0], [1, 0.5]]}]}]})");
  for (const auto& [k, v] : body.items()) j["bodies"][0][k] = v;
  j["bodies"][0]["scheme"] = scheme;
  const fs::path dir = fresh_dir("presets_" + tag);
  {
    std::ofstream o(dir / "case.json");
    o << j.dump();
  }
  const RunResult r = run_lagfsi("check \"" + (dir / "case.json").string() + "\"", dir);
  Checked c{r.exit_code, r.stderr_text, {}};
  if (r.exit_code == 0) {
    std::ifstream in(dir / "stdout.txt");
    std::stringstream ss;
    ss << in.rdbuf();
    c.body = nlohmann::json::parse(ss.str())["bodies"][0];
  }
  return c;
}

void expect_family(const nlohmann::json& b, const std::string& preset, const std::string& detection,
                   const std::string& walls, const std::string& friction, const std::string& correction) {
  EXPECT_EQ(b["preset"], preset);
  EXPECT_EQ(b["domain_detection"], detection);
  EXPECT_EQ(b["wall_model"], walls);
  EXPECT_EQ(b["wall_friction"], friction);
  EXPECT_EQ(b["scheme"]["volume_correction"], correction);
}

TEST(FluidPresets, TheMonolithicSchemeWithRemeshingIsConservative) {
  const Checked c = check_tank(nlohmann::json::object(), nlohmann::json::object(), "monolithic");
  ASSERT_EQ(c.exit_code, 0) << c.stderr_text;
  expect_family(c.body, "conservative", "advected", "constraints", "navier", "particle");
  EXPECT_EQ(c.body["scheme"]["free_surface_pressure"], "robin");
}

TEST(FluidPresets, TheFractionalStepIsClassic) {
  const Checked c = check_tank(nlohmann::json::object(), {{"type", "fractional_step"}}, "fractional");
  ASSERT_EQ(c.exit_code, 0) << c.stderr_text;
  expect_family(c.body, "classic", "alpha", "particles", "held", "surface");
}

TEST(FluidPresets, AChosenPresetGivesItsFamilyToEitherScheme) {
  const Checked fs = check_tank({{"preset", "conservative"}}, {{"type", "fractional_step"}}, "fs_conservative");
  ASSERT_EQ(fs.exit_code, 0) << fs.stderr_text;
  expect_family(fs.body, "conservative", "advected", "constraints", "navier", "particle");
  EXPECT_DOUBLE_EQ(fs.body["scheme"]["volume_relaxation_time"].get<double>(), 20 * 0.01);
  const Checked mono = check_tank({{"preset", "classic"}}, nlohmann::json::object(), "monolithic_classic");
  ASSERT_EQ(mono.exit_code, 0) << mono.stderr_text;
  expect_family(mono.body, "classic", "alpha", "particles", "held", "surface");
  EXPECT_EQ(mono.body["scheme"]["free_surface_pressure"], "dirichlet");
}

TEST(FluidPresets, AKeyGivenInTheCaseOverridesItsPresetsValue) {
  const Checked c = check_tank({{"wall_model", "particles"}}, nlohmann::json::object(), "override");
  ASSERT_EQ(c.exit_code, 0) << c.stderr_text;
  expect_family(c.body, "conservative", "advected", "particles", "held", "particle");
  EXPECT_EQ(c.body["scheme"]["free_surface_pressure"], "robin");
}

TEST(FluidPresets, TheConservativePresetOnAFixedMeshIsRefusedNamingTheKey) {
  const Checked c = check_tank({{"preset", "conservative"}, {"remesh", false}}, nlohmann::json::object(), "fixed");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.stderr_text.find("/bodies/0/preset"), std::string::npos) << c.stderr_text;
  const Checked bad = check_tank({{"preset", "gentle"}}, nlohmann::json::object(), "unknown");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.stderr_text.find("/bodies/0/preset"), std::string::npos) << bad.stderr_text;
}

}  // namespace
