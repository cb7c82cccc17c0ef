// The fluid's defaults that follow from other keys (fluid_defaults.hpp), and the integrator a fluid body prefers.
#include "fluid_defaults.hpp"

#include <lagfsi/fluid/fluid_model.hpp>

namespace lagfsi::fluid {

namespace {

bool has_open_boundary(const Json& body) {
  if (!body.is_object() || !body.contains("boundaries") || !body.at("boundaries").is_array()) return false;
  for (const Json& b : body.at("boundaries")) {
    const std::string type = peek(b, "type", "");
    if (type == "inflow" || type == "outflow") return true;
  }
  return false;
}

/// An inflow of the body holds a layer ("hold": "layer"): its flux jitters from step to step.
bool has_layer_inflow(const Json& body) {
  if (!body.is_object() || !body.contains("boundaries") || !body.at("boundaries").is_array()) return false;
  for (const Json& b : body.at("boundaries"))
    if (peek(b, "type", "") == "inflow" && peek(b, "hold", "points") == "layer") return true;
  return false;
}

}  // namespace

std::string peek(const Json& o, const char* key, const std::string& fallback) {
  return o.is_object() && o.contains(key) && o.at(key).is_string() ? o.at(key).get<std::string>() : fallback;
}

FluidDefaults fluid_defaults(const Json& body) {
  const bool remesh =
      !(body.is_object() && body.contains("remesh") && body.at("remesh").is_boolean()) || body.at("remesh").get<bool>();
  const Json scheme = body.is_object() && body.contains("scheme") ? body.at("scheme") : Json::object();
  FluidDefaults d;
  // The preset: conservative for the monolithic scheme with remeshing, classic otherwise (a fixed mesh is classic
  // whatever it asks: read_body_keys refuses the combination).
  d.preset = remesh && peek(scheme, "type", "monolithic_pspg") == "monolithic_pspg" ? "conservative" : "classic";
  const bool conservative = remesh && peek(body, "preset", d.preset) == "conservative";
  d.detection = conservative ? "advected" : "alpha";
  const std::string detection = peek(body, "domain_detection", d.detection);
  const bool alpha = detection == "alpha";
  // 0.3 for "advected", where it keeps the splash's landings from adding area (cases/studies/conservation).
  d.contact_gap = detection == "advected" ? 0.3 : 0.0;
  d.wall_model = conservative && !alpha ? "constraints" : "particles";
  d.wall_friction = conservative && peek(body, "wall_model", d.wall_model) == "constraints" ? "navier" : "held";
  // Open boundaries: p = 0 exactly on the free surface, the outlet's condition too (the weak Robin pressure left the
  // pressure level of the confined channel flow of cases/channel_poiseuille ringing: its pressure drop's standard
  // deviation over 1-3 s was 64 Pa against 6 with p = 0, for a mean of 18).
  d.free_surface_pressure = conservative && !alpha && !has_open_boundary(body) ? "robin" : "dirichlet";
  // The alpha shape changes the area at every remesh and needs the surface correction; the advected and
  // level-set detections keep it where the topology does not change, and particle volumes return the rest.
  d.volume_correction = alpha ? "surface" : conservative ? "particle" : "none";
  // Open boundaries (an inflow or an outflow): the water's area is no longer a constant each particle keeps; the
  // surface correction puts what the remeshing changed back at the free surface instead (the monolithic scheme on
  // cases/open_channel_flap with walls as constraints: without a correction the water balance is off by 60 % of the
  // initial water in 4 s, with it by 0.02 % in 2 s).
  if (has_open_boundary(body) && d.volume_correction == "particle") d.volume_correction = "surface";
  // Without one (the fractional step with the advected or level-set detection), the steps' own area error stays:
  // where the divergence is held only weakly (in elements with a wall particle, and through the Laplacian's
  // stabilization) Turek & Hron's CFD1 made 0.6 % of its inflow in 5 s, and the flow rate downstream was 0.4 % above
  // the inflow's. The uniform source returns it through the outlet (an outflow sets the pressure level, so no
  // pressure builds up to contract the water); decision 0019. Not behind a held layer, whose flux jitters: the source
  // would turn each jitter into a kick on the whole confined column.
  if (has_open_boundary(body) && d.volume_correction == "none" && !has_layer_inflow(body))
    d.volume_correction = "source";
  // The "particle" correction returns each particle's area over a few steps (0.01 s: a tuned value, the best of
  // 0.005-0.03 s on the three dam breaks under generalized-alpha; docs/decisions/0005-particle-volumes.md); the global
  // "source" over 0.1 s.
  d.volume_relaxation_time = peek(scheme, "volume_correction", d.volume_correction) == "particle" ? 0.01 : 0.1;
  return d;
}

}  // namespace lagfsi::fluid

namespace lagfsi {

Json fluid_preferred_integrator(const Json& body) {
  const Json scheme = body.is_object() && body.contains("scheme") ? body.at("scheme") : Json::object();
  if (fluid::peek(scheme, "type", "monolithic_pspg") != "monolithic_pspg") return nullptr;
  const fluid::FluidDefaults d = fluid::fluid_defaults(body);
  const std::string surface = fluid::peek(scheme, "free_surface_pressure", d.free_surface_pressure);
  // With wall particles the trapezoidal rule keeps more of the water (dam_break_tank, wall particles, advected,
  // Robin, 1 s: water within 1.68 % and 292 particles put back from beyond a wall under generalized-alpha, 0.63 %
  // and 68 under Newmark; the obstacle's 1.49 % and 569 against 1.33 % and 299;
  // docs/decisions/0006-generalized-alpha-default.md). Probably the fluid is held off the walls by the pressure at the
  // evaluation point alone, and generalized-alpha's end positions, extrapolated from it, overshoot between wall
  // particles in a splash.
  // An inflow or outflow with walls as constraints asks for it too: the open channel over an elastic flap
  // (cases/open_channel_flap, case_monolithic.json) diverges under the trapezoidal rule (the flap's force swings from
  // 0.45 s and grows tenfold by 0.75 s) and runs under generalized-alpha.
  const std::string walls = fluid::peek(body, "wall_model", d.wall_model);
  return (surface == "robin" || fluid::has_open_boundary(body)) && walls == "constraints"
             ? Json{{"type", "generalized_alpha"}, {"rho_inf", 0.8}}
             : Json(nullptr);
}

}  // namespace lagfsi
