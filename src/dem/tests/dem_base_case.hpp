#pragma once
// The small DEM case the DEM unit tests mutate: a hexagonal bed of 2 mm discs in a box under gravity, 10 steps.
#include <nlohmann/json.hpp>

#include <string>

inline nlohmann::json dem_base_case(const std::string& name) {
  nlohmann::json c = nlohmann::json::parse(R"({
    "analysis": {"type": "dynamic", "dt": 1e-4, "end_time": 1e-3},
    "gravity": [0, -9.81],
    "bodies": [{
      "name": "bed", "type": "dem",
      "material": {"density": 2500},
      "contact": {"law": "linear", "kn": 1e5, "damping_ratio": 0.1, "friction": 0.5},
      "discs": [{"type": "hex_lattice", "region": {"type": "rectangle", "origin": [0, 0], "size": [0.1, 0.05]},
                 "radius": 0.002}],
      "walls": [{"name": "box", "points": [[0, 0.2], [0, 0], [0.1, 0], [0.1, 0.2]]}]
    }]
  })");
  c["name"] = name;
  return c;
}
