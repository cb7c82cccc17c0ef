#include "case_builder.hpp"

#include "input_checks.hpp"

#include <lagfsi/app/model_registry.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/fsi/dirichlet_neumann.hpp>

#include <algorithm>
#include <functional>
#include <iostream>
#include <new>

namespace lagfsi {

namespace fs = std::filesystem;

namespace {

const KeyTable kCaseKeys(
    "/", "The case file: a JSON object (comments allowed) with these top-level keys.",
    {{"name", "", "Case name (output folder out/<name>); default (empty): the case file's name without .json."},
     {"description", "", "Free text describing the case (not used by the program)."},
     {"analysis", nullptr, "Static or dynamic analysis and its solver settings (see /analysis)."},
     {"gravity", Json::array({0.0, 0.0}), "Acceleration of gravity [gx, gy] (m/s^2), e.g. [0, -9.81]."},
     {"bodies", nullptr,
      "The bodies (at least one), each an object whose `type` is solid, shell, fluid, mpm, dem or efg (see "
      "/bodies/* (type solid) and the others)."},
     {"couplings", Json::array(),
      "Fluid-structure couplings between two bodies (see /couplings/* (type dirichlet_neumann))."},
     {"probes", Json::array(),
      "Quantities sampled at every step into probes.csv (see the /probes/* sections, by body type)."},
     {"output", Json::object(), "What is written and how often (see /output)."}});

const KeyTable kOutputKeys("/output", "What a run writes besides probes.csv, log.csv and summary.json.",
                           {{"every", 1, "Write the ParaView output every this many steps."},
                            {"vtk", true, "Write the ParaView series (<body>.pvd and <body>/*.vtu)."},
                            {"checkpoint", Json::object(), "Checkpoint settings (see /output/checkpoint)."}});

}  // namespace

const Json& case_defaults() {
  static const Json d = kCaseKeys.defaults();
  return d;
}

const std::map<std::string, ModelBuilder>& model_registry() {
  static const std::map<std::string, ModelBuilder> r = {
      {"solid", make_solid_model}, {"shell", make_solid_model}, {"fluid", make_fluid_model},
      {"mpm", make_mpm_model},     {"dem", make_dem_model},     {"efg", make_efg_model},
  };
  return r;
}

const std::map<std::string, IntegratorPreference>& integrator_preferences() {
  static const std::map<std::string, IntegratorPreference> r = {{"fluid", fluid_preferred_integrator}};
  return r;
}

namespace {

/// The integrator the bodies ask for when the case names none (the first body with a preference), else Newmark.
Json default_integrator(const Json& bodies) {
  if (bodies.is_array())
    for (const Json& body : bodies) {
      if (!body.is_object() || !body.contains("type") || !body.at("type").is_string()) continue;
      const auto it = integrator_preferences().find(body.at("type").get<std::string>());
      if (it == integrator_preferences().end()) continue;
      if (Json p = it->second(body); p.is_object()) return p;
    }
  return Json{{"type", "newmark"}};
}

/// Registry of coupling types (fsi/): the "type" string of an entry of "couplings" to its builder, which
/// gets the two bodies it couples.
using CouplingBuilder = std::function<std::unique_ptr<PhysicsModel>(Params, const CaseContext&, PhysicsModel& fluid,
                                                                    PhysicsModel& structure)>;
const std::map<std::string, CouplingBuilder>& coupling_registry() {
  static const std::map<std::string, CouplingBuilder> r = {{"dirichlet_neumann", fsi::make_dirichlet_neumann}};
  return r;
}

Case build_case(const RunOptions& opt, bool for_check) {
  Case c;
  c.root = Params::load(opt.case_file);
  for (const auto& o : opt.overrides) apply_override(c.root.json(), o);
  c.root.validate(kCaseKeys);
  c.name = c.root.string("name").empty() ? opt.case_file.stem().string() : c.root.identifier("name");
  c.ctx.case_file = opt.case_file;
  c.ctx.quiet = opt.quiet;
  c.ctx.base_dir = opt.case_file.parent_path();
  c.ctx.out_dir = opt.out_dir.empty() ? fs::path("out") / c.name : opt.out_dir;
  c.ctx.analysis = read_analysis(c.root.at("analysis"), c.warnings, default_integrator(c.root.json().at("bodies")));
  c.ctx.gravity = c.root.vec2("gravity");
  Params out = c.root.at("output");
  out.validate(kOutputKeys);
  c.output_every = out.integer("every", 1);
  c.vtk = out.boolean("vtk");
  c.checkpoint = read_checkpoint_settings(out.at("checkpoint"));
  (void)for_check;

  Params bodies = c.root.at("bodies");
  if (bodies.size() == 0) bodies.fail("at least one body is needed");
  std::vector<std::string> types;
  for (const auto& [k, v] : model_registry()) types.push_back(k);
  for (size_t i = 0; i < bodies.size(); ++i) {
    Params b = bodies.at(i);
    if (!b.json().is_object()) b.fail("expected an object");
    if (!b.has("type")) b.fail("type", "required key is missing");
    const std::string type = b.choice("type", types);
    c.models.push_back(model_registry().at(type)(b, c.ctx));
    for (const auto& w : c.models.back()->warnings()) c.warnings.push_back(w);
    for (size_t j = 0; j + 1 < c.models.size(); ++j)
      if (c.models[j]->name() == c.models.back()->name()) b.fail("name", "duplicate body name");
  }
  // Couplings: each takes two bodies out of the driver's hands.
  Params couplings = c.root.at("couplings");
  std::vector<std::string> coupling_types;
  for (const auto& [k, v] : coupling_registry()) coupling_types.push_back(k);
  std::vector<PhysicsModel*> coupled;
  auto body_named = [&](Params q, const std::string& key) -> PhysicsModel& {
    if (!q.has(key)) q.fail(key, "required key is missing");
    const std::string nm = q.string(key);
    for (auto& m : c.models)
      if (m->name() == nm) {
        if (std::find(coupled.begin(), coupled.end(), m.get()) != coupled.end())
          q.fail(key, "body '" + nm + "' is already coupled");
        coupled.push_back(m.get());
        return *m;
      }
    q.fail(key, "no body named '" + nm + "'");
  };
  for (size_t i = 0; i < couplings.size(); ++i) {
    Params q = couplings.at(i);
    if (!q.json().is_object()) q.fail("expected an object");
    if (!q.has("type")) q.fail("type", "required key is missing");
    const std::string type = q.choice("type", coupling_types);
    PhysicsModel& fluid = body_named(q, "fluid");
    PhysicsModel& structure = body_named(q, "structure");
    c.couplings.push_back(coupling_registry().at(type)(q, c.ctx, fluid, structure));
    for (const auto& m : c.models)
      if (m->name() == c.couplings.back()->name()) q.fail("name", "a body has the same name");
  }
  for (auto& m : c.models)
    if (std::find(coupled.begin(), coupled.end(), m.get()) == coupled.end()) c.steppers.push_back(m.get());
  if (c.checkpoint.active() || opt.restart) {
    std::vector<PhysicsModel*> all;
    for (const auto* list : {&c.models, &c.couplings})
      for (const auto& m : *list) all.push_back(m.get());
    check_checkpointable(all, out, opt.restart, opt.case_file);
  }
  for (auto& m : c.couplings) c.steppers.push_back(m.get());

  Params probes = c.root.at("probes");
  std::vector<std::string> names;
  for (size_t i = 0; i < probes.size(); ++i) {
    Params p = probes.at(i);
    if (!p.json().is_object()) p.fail("expected an object");
    if (!p.has("name")) p.fail("name", "required key is missing");
    if (!p.has("type")) p.fail("type", "required key is missing");
    if (!p.has("body")) p.fail("body", "required key is missing");
    (void)p.identifier("name");  // a column of probes.csv: no commas, quotes or line breaks
    const std::string body = p.string("body");
    PhysicsModel* m = nullptr;
    for (auto& mm : c.models)
      if (mm->name() == body) m = mm.get();
    for (auto& mm : c.couplings)
      if (mm->name() == body) m = mm.get();
    if (!m) p.fail("body", "no body named '" + body + "'");
    auto probe = m->make_probe(p);
    for (const auto& col : probe->columns()) {
      if (col == "time" || std::find(names.begin(), names.end(), col) != names.end())
        p.fail("name", "duplicate probe column '" + col + "'");
      names.push_back(col);
    }
    c.probes.push_back(std::move(probe));
  }
  // What no single body can see: output names shared by two bodies, bodies that overlap.
  check_output_names(c.root);
  check_overlaps(c.root);
  return c;
}

}  // namespace

std::unique_ptr<Case> build_case_or_report(const RunOptions& opt, bool for_check) {
  try {
    return std::make_unique<Case>(build_case(opt, for_check));
  } catch (const InputError& e) {
    std::cerr << "lagfsi: error: " << e.what() << "\n";
  } catch (const std::bad_alloc&) {
    std::cerr << "lagfsi: error: " << opt.case_file.string()
              << ": out of memory while building the case (a mesh size, spacing or length far from the others?)\n";
  } catch (const std::exception& e) {
    std::cerr << "lagfsi: error: " << opt.case_file.string() << ": " << e.what() << "\n";
  }
  return nullptr;
}

std::vector<PhysicsModel*> all_models(const Case& c) {
  std::vector<PhysicsModel*> all;
  for (const auto* list : {&c.models, &c.couplings})
    for (const auto& m : *list) all.push_back(m.get());
  return all;
}

}  // namespace lagfsi
