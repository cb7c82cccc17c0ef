// Whole-case input checks (input_checks.hpp).
#include "input_checks.hpp"

#include "checkpoint.hpp"
#include "output_lock.hpp"
#include "overlap.hpp"

#include <lagfsi/case.hpp>
#include <lagfsi/text.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

namespace lagfsi {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string num(double x) {
  std::ostringstream o;
  o.precision(4);
  o << x;
  return o.str();
}

/// The files and folders a body writes into the output folder (see the models' write_output).
std::vector<std::string> body_outputs(const std::string& name, const std::string& type) {
  std::vector<std::string> out{name + ".pvd", name};
  if (type == "fluid") out.insert(out.end(), {name + "_walls.pvd", name + "_walls"});
  if (type == "mpm") out.insert(out.end(), {name + "_grid.pvd", name + "_grid", name + "_particles.csv"});
  return out;
}

/// A body's regions (fluid and MPM "regions", a solid's "geometry", a shell's mid-line widened to its
/// thickness: a rectangle per segment) as plane regions with their JSON paths.
struct Shape {
  PlaneRegion region;
  std::string key;  // relative to the body: "regions/0", "geometry"
};

bool read_shape(const Json& g, PlaneRegion& r) {
  if (!g.is_object() || !g.contains("type") || !g["type"].is_string()) return false;
  const std::string type = g["type"];
  auto point = [](const Json& p) { return Vec2(p[0].get<double>(), p[1].get<double>()); };
  if (type == "rectangle") {
    const Vec2 o = g.contains("origin") ? point(g["origin"]) : Vec2::Zero(), s = point(g["size"]);
    r.rings = {{o, o + Vec2(s.x(), 0), o + s, o + Vec2(0, s.y())}};
    return true;
  }
  if (type == "circle_cut") {
    // The arc in 128 pieces per turn: its chords cut off at most 0.03 % of the radius.
    const double radius = g["radius"].get<double>();
    r.rings = {circle_cut_outline(Params(g, "", ""), 2 * std::numbers::pi * radius / 128)};
    return true;
  }
  if (type != "polygon") return false;
  std::vector<Vec2> outer;
  for (const auto& p : g["points"]) outer.push_back(point(p));
  r.rings = {outer};
  if (g.contains("holes"))
    for (const auto& h : g["holes"]) {
      std::vector<Vec2> ring;
      for (const auto& p : h) ring.push_back(point(p));
      r.rings.push_back(ring);
    }
  return true;
}

std::vector<Shape> shapes_of(const Json& b) {
  std::vector<Shape> out;
  const std::string type = b.value("type", "");
  PlaneRegion r;
  if (type == "solid" && b.contains("geometry") && read_shape(b["geometry"], r)) out.push_back({r, "geometry"});
  if (type == "shell" && b.contains("geometry") && b.value("thickness", 0.0) > 0) {
    const Json& g = b["geometry"];
    auto point = [](const Json& p) { return Vec2(p[0].get<double>(), p[1].get<double>()); };
    std::vector<Vec2> line;
    if (g.value("type", "") == "line") line = {point(g["from"]), point(g["to"])};
    if (g.value("type", "") == "polyline")
      for (const auto& p : g["points"]) line.push_back(point(p));
    const double half = 0.5 * b["thickness"].get<double>();
    for (size_t s = 0; s + 1 < line.size(); ++s) {
      const Vec2 d = line[s + 1] - line[s];
      if (!(d.norm() > 0)) continue;
      const Vec2 n = half * Vec2(-d.y(), d.x()) / d.norm();
      r.rings = {{line[s] - n, line[s + 1] - n, line[s + 1] + n, line[s] + n}};
      out.push_back({r, "geometry"});
    }
  }
  if ((type == "fluid" || type == "mpm") && b.contains("regions"))
    for (size_t j = 0; j < b["regions"].size(); ++j)
      if (read_shape(b["regions"][j], r)) out.push_back({r, "regions/" + std::to_string(j)});
  return out;
}

double diameter(const PlaneRegion& r) {
  Vec2 lo = Vec2::Constant(INFINITY), hi = -lo;
  for (const auto& p : r.rings.front()) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

}  // namespace

void check_output_names(const Params& root) {
  // Owner of each output name (lower case): the run's own files, then each body's.
  std::map<std::string, std::string> owner;
  const std::vector<std::string> run_files{"log.csv",       "probes.csv",        "summary.json", "resolved_case.json",
                                           kCheckpointFile, kCheckpointPrevFile, kLockFileName};
  for (const auto& f : run_files) owner[lower(f)] = "the run itself";
  const Params bodies = root.at("bodies");
  for (size_t i = 0; i < bodies.size(); ++i) {
    const Params b = bodies.at(i);
    const std::string name = b.string("name"), type = b.string("type");
    for (const auto& f : run_files)
      if (lower(name) == lower(f.substr(0, f.find('.'))) && f[0] != '.')
        b.fail("name", "'" + name + "' is the name of the run's " + f + ": choose another body name");
    for (const auto& f : body_outputs(name, type)) {
      const auto [it, fresh] = owner.emplace(lower(f), "body '" + name + "'");
      if (!fresh)
        b.fail("name", "its output '" + f + "' is also written by " + it->second +
                           " (file names are compared ignoring case): choose another body name");
      // The .tmp through which a file is replaced belongs to it too.
      owner.emplace(lower(f) + ".tmp", "body '" + name + "'");
    }
  }
}

void check_overlaps(const Params& root) {
  const Params bodies = root.at("bodies");
  const Json& all = bodies.json();
  std::vector<std::vector<Shape>> shapes;
  for (const auto& b : all) shapes.push_back(shapes_of(b));
  for (size_t i = 0; i < all.size(); ++i) {
    const Params b = bodies.at(i);
    for (size_t k = 0; k < i; ++k) {
      const std::string other = all[k].value("name", "");
      for (const Shape& s : shapes[i])
        for (const Shape& t : shapes[k]) {
          const double common = overlap_area(s.region, t.region);
          const double smaller = std::min(region_area(s.region), region_area(t.region));
          if (common > 1e-3 * smaller)
            b.fail(s.key, "overlaps body '" + other + "' (its " + t.key + "; " + num(common) + " in common, " +
                              num(100 * common / smaller) + " % of the smaller)");
        }
    }
    // A solid or shell crossed by the rigid walls of a fluid (either order in the file).
    if (all[i].value("type", "") != "solid" && all[i].value("type", "") != "shell") continue;
    for (size_t k = 0; k < all.size(); ++k) {
      if (all[k].value("type", "") != "fluid" || !all[k].contains("walls")) continue;
      const Json& walls = all[k]["walls"];
      for (const Shape& s : shapes[i])
        for (size_t w = 0; w < walls.size(); ++w) {
          std::vector<Vec2> line;
          for (const auto& p : walls[w]["points"]) line.push_back(Vec2(p[0].get<double>(), p[1].get<double>()));
          const double d = diameter(s.region);
          const double in = length_inside(s.region, line, 1e-6 * d);
          if (in > 1e-4 * d)
            b.fail(s.key, "is crossed by the wall '" + walls[w].value("name", "wall" + std::to_string(w)) +
                              "' of body '" + all[k].value("name", "") + "' (" + num(in) + " of it inside)");
        }
    }
  }
}

std::vector<std::string> check_integrator_stability(Params it) {
  std::vector<std::string> warnings;
  if (it.string("type") == "newmark") {
    const double beta = it.number("beta"), gamma = it.number("gamma");
    if (!(beta > 0)) it.fail("beta", "must be positive (beta = 0 is the explicit central_difference)");
    if (gamma < 0.5) it.fail("gamma", "must be at least 1/2 (gamma < 1/2 is unstable)");
    if (beta < 0.5 * gamma) {
      const double w_crit = 1.0 / std::sqrt(0.5 * gamma - beta);
      const std::string what = "beta = " + num(beta) + " < gamma / 2 = " + num(0.5 * gamma) +
                               ": conditionally stable (omega dt <= " + num(w_crit) + " for every mode)";
      if (!it.boolean("allow_conditionally_stable"))
        it.fail("beta", what +
                            "; unconditional stability needs beta >= gamma / 2 (set \"allow_conditionally_stable\": "
                            "true to run it anyway)");
      warnings.push_back(it.path() + ": " + what + ", chosen with allow_conditionally_stable");
    }
  } else if (it.string("type") == "generalized_alpha") {
    const double r = it.number("rho_inf");
    if (r < 0 || r > 1) it.fail("rho_inf", "must lie in [0, 1]");
  }
  return warnings;
}

void check_output_folder(const fs::path& case_file, const fs::path& out_dir) {
  std::error_code ec1, ec2;
  const fs::path in = fs::weakly_canonical(fs::absolute(case_file).parent_path(), ec1);
  const fs::path out = fs::weakly_canonical(fs::absolute(out_dir), ec2);
  if (!ec1 && !ec2 && in == out)
    throw InputError(case_file.string(), "",
                     "the output folder " + echo(out_dir.string(), 200) +
                         " is the case file's own folder, whose files the run would write over: give another with -o");
}

}  // namespace lagfsi
