// Disc generators of the DEM body (src/dem/include/lagfsi/dem/dem_particles.hpp): lists, hexagonal lattices and
// random sequential addition in rectangles and polygons.
#include <lagfsi/dem/dem_particles.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <unordered_map>

namespace lagfsi::dem {

namespace {

const char* const kVelocityDoc = "Initial velocity [vx, vy] (m/s) of the generator's discs.";
const char* const kAngularDoc = "Initial angular velocity (rad/s) of the generator's discs.";
const char* const kRegionDoc = "The region (see /bodies/*/discs/*/region (dem body, ...)).";

const KeyTable kDemRectangleKeys("/bodies/*/discs/*/region (dem body, type rectangle)", "A rectangle.",
                                 {{"type", "rectangle", "`rectangle`."},
                                  {"origin", nullptr, "Lower-left corner [x, y] (m)."},
                                  {"size", nullptr, "Width and height [w, h] (m)."}});

const KeyTable kDemPolygonKeys("/bodies/*/discs/*/region (dem body, type polygon)", "A polygon.",
                               {{"type", "polygon", "`polygon`."},
                                {"points", nullptr, "Outline [[x, y], ...] (m), at least 3 points."}});

const KeyTable kDemListKeys("/bodies/*/discs/* (dem body, type list)", "Discs given one by one.",
                            {{"type", "list", "`list`."},
                             {"discs", nullptr, "The discs [[x, y, r], ...] (m)."},
                             {"velocity", Json::array({0.0, 0.0}), kVelocityDoc},
                             {"angular_velocity", 0.0, kAngularDoc}});

const KeyTable kDemHexKeys(
    "/bodies/*/discs/* (dem body, type hex_lattice)",
    "A hexagonal lattice of pitch 2 r (1 + gap), the first row on the region's bottom, every disc inside.",
    {{"type", "hex_lattice", "`hex_lattice`."},
     {"region", nullptr, kRegionDoc},
     {"radius", nullptr, "Disc radius r (m)."},
     {"gap", 0.0, "Relative gap between neighbouring discs."},
     {"velocity", Json::array({0.0, 0.0}), kVelocityDoc},
     {"angular_velocity", 0.0, kAngularDoc}});

const KeyTable kDemRandomKeys(
    "/bodies/*/discs/* (dem body, type random)",
    "Random sequential addition of non-overlapping discs until a packing fraction or a count (a loose pack).",
    {{"type", "random", "`random`."},
     {"region", nullptr, kRegionDoc},
     {"radius", nullptr, "Disc radius r (m), or [r_min, r_max] for radii uniform between them."},
     {"fraction", 0.5, "Target packing fraction, at most 0.6."},
     {"count", 0, "Number of discs (0: until the fraction)."},
     {"seed", 1, "Seed of the random numbers."},
     {"attempts", 20000, "Failed placements in a row before the generator stops (at most 1e6; 2e7 in all)."},
     {"velocity", Json::array({0.0, 0.0}), kVelocityDoc},
     {"angular_velocity", 0.0, kAngularDoc}});

}  // namespace

double polygon_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2& u = p[i];
    const Vec2& w = p[(i + 1) % p.size()];
    a += u.x() * w.y() - w.x() * u.y();
  }
  return 0.5 * std::abs(a);
}

bool inside_polygon(const std::vector<Vec2>& p, const Vec2& x) {
  bool in = false;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i].y() > x.y()) != (p[j].y() > x.y()) &&
        x.x() < (p[j].x() - p[i].x()) * (x.y() - p[i].y()) / (p[j].y() - p[i].y()) + p[i].x())
      in = !in;
  }
  return in;
}

double distance_to_boundary(const std::vector<Vec2>& p, const Vec2& x) {
  double d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2& a = p[i];
    const Vec2& b = p[(i + 1) % p.size()];
    const Vec2 ab = b - a;
    const double s = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    d = std::min(d, (a + s * ab - x).norm());
  }
  return d;
}

namespace {

bool fits(const std::vector<Vec2>& poly, const Vec2& x, double r) {
  // a tolerance of 1e-9 r lets a lattice row touch the region's edge exactly
  return inside_polygon(poly, x) && distance_to_boundary(poly, x) >= r * (1 - 1e-9);
}

/// Discs of radius r placed among coordinates as large as the region's: past 1e9 r, x + r rounds to about x
/// (a lattice's next column would fall on the last one and the generator would not advance).
void check_resolution(Params d, const std::vector<Vec2>& poly, double r) {
  double c = 0;
  for (const auto& q : poly) c = std::max(c, q.cwiseAbs().maxCoeff());
  if (!(c < 1e9 * r)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "coordinates up to %.3g m do not resolve discs of radius %.3g m (at most 1e9 radii)",
                  c, r);
    d.fail("region", buf);
  }
}

void bounds(const std::vector<Vec2>& poly, Vec2& lo, Vec2& hi) {
  lo = hi = poly[0];
  for (const auto& q : poly) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
}

}  // namespace

std::vector<DiscSpec> hex_lattice(const std::vector<Vec2>& poly, double r, double gap) {
  Vec2 lo, hi;
  bounds(poly, lo, hi);
  const double pitch = 2 * r * (1 + gap), dy = pitch * std::sqrt(3.0) / 2;
  std::vector<DiscSpec> out;
  for (int row = 0;; ++row) {
    const double y = lo.y() + r + row * dy;
    if (y > hi.y() - r * (1 - 1e-9)) break;
    for (int col = 0;; ++col) {
      const double x = lo.x() + r + (row % 2 ? 0.5 * pitch : 0.0) + col * pitch;
      if (x > hi.x() - r * (1 - 1e-9)) break;
      const Vec2 c(x, y);
      if (fits(poly, c, r)) out.push_back({c, r, Vec2::Zero(), 0.0, 0});
    }
  }
  return out;
}

std::vector<DiscSpec> random_pack(const std::vector<Vec2>& poly, double r_min, double r_max, double fraction, int count,
                                  unsigned seed, int attempts, PackReport* report, long max_trials) {
  Vec2 lo, hi;
  bounds(poly, lo, hi);
  const double area = polygon_area(poly);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(lo.x(), hi.x()), uy(lo.y(), hi.y()), ur(r_min, r_max);
  // a hash grid of cell 2 r_max holds the placed discs
  const double h = 2 * r_max;
  auto key = [&](long i, long j) { return i * 1000003L + j; };
  std::unordered_map<long, std::vector<size_t>> cells;
  std::vector<DiscSpec> out;
  double filled = 0;
  int failures = 0;
  long trials = 0;
  while (failures < attempts && trials < max_trials && (count <= 0 || static_cast<int>(out.size()) < count) &&
         (fraction <= 0 || filled < fraction * area)) {
    ++trials;
    const double r = r_max > r_min ? ur(rng) : r_min;
    const Vec2 c(ux(rng), uy(rng));
    bool ok = fits(poly, c, r);
    const long ci = static_cast<long>(std::floor((c.x() - lo.x()) / h)),
               cj = static_cast<long>(std::floor((c.y() - lo.y()) / h));
    for (long a = ci - 1; ok && a <= ci + 1; ++a)
      for (long b = cj - 1; ok && b <= cj + 1; ++b) {
        auto it = cells.find(key(a, b));
        if (it == cells.end()) continue;
        for (size_t q : it->second)
          if ((out[q].x - c).squaredNorm() < (out[q].r + r) * (out[q].r + r)) {
            ok = false;
            break;
          }
      }
    if (!ok) {
      ++failures;
      continue;
    }
    failures = 0;
    cells[key(ci, cj)].push_back(out.size());
    out.push_back({c, r, Vec2::Zero(), 0.0, 0});
    filled += std::numbers::pi * r * r;
  }
  if (report) {
    report->fraction = filled / area;
    report->trials = trials;
    report->jammed = failures >= attempts;
  }
  return out;
}

std::vector<Vec2> read_region(Params region) {
  if (!region.json().is_object() || !region.has("type")) region.fail("type", "required key is missing");
  const std::string t = region.choice("type", {"rectangle", "polygon"});
  if (t == "rectangle") {
    region.validate(kDemRectangleKeys);
    const Vec2 o = region.vec2("origin"), s = region.vec2("size");
    if (!(s.x() > 0 && s.y() > 0)) region.fail("size", "must be positive");
    return {o, o + Vec2(s.x(), 0), o + s, o + Vec2(0, s.y())};
  }
  region.validate(kDemPolygonKeys);
  auto p = region.points("points");
  if (p.size() < 3 || !(polygon_area(p) > 0)) region.fail("points", "a polygon needs at least 3 points and an area");
  return p;
}

std::vector<DiscSpec> generate_discs(Params discs, std::vector<std::string>* warnings) {
  std::vector<DiscSpec> out;
  if (discs.size() == 0) discs.fail("at least one generator is needed");
  for (size_t g = 0; g < discs.size(); ++g) {
    Params d = discs.at(g);
    if (!d.json().is_object() || !d.has("type")) d.fail("type", "required key is missing");
    const std::string t = d.choice("type", {"list", "hex_lattice", "random"});
    std::vector<DiscSpec> made;
    if (t == "list") {
      d.validate(kDemListKeys);
      Params l = d.at("discs");
      for (size_t i = 0; i < l.size(); ++i) {
        const auto v = l.at(i).json();
        if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
          l.at(i).fail("expected [x, y, r]");
        const double r = v[2].get<double>();
        if (!(r > 0) || !std::isfinite(r)) l.at(i).fail("the radius must be positive");
        if (!(std::abs(v[0].get<double>()) < 1e9 * r && std::abs(v[1].get<double>()) < 1e9 * r))
          l.at(i).fail("the centre is more than 1e9 radii from the origin: its coordinates do not resolve the radius");
        made.push_back({Vec2(v[0].get<double>(), v[1].get<double>()), r, Vec2::Zero(), 0.0, 0});
      }
    } else if (t == "hex_lattice") {
      d.validate(kDemHexKeys);
      const double r = d.positive("radius");
      const auto poly = read_region(d.at("region"));
      check_resolution(d, poly, r);
      Vec2 lo, hi;
      bounds(poly, lo, hi);
      if ((hi - lo).x() * (hi - lo).y() / (r * r) > 4e7) d.fail("radius", "more than 1e7 discs: check the radius");
      made = hex_lattice(poly, r, d.non_negative("gap"));
    } else {
      d.validate(kDemRandomKeys);
      double r0, r1;
      if (d.json().at("radius").is_array()) {
        const auto rr = d.numbers("radius");
        if (rr.size() != 2 || !(rr[0] > 0 && rr[1] >= rr[0]))
          d.fail("radius", "expected [r_min, r_max], 0 < r_min <= r_max");
        r0 = rr[0];
        r1 = rr[1];
      } else {
        r0 = r1 = d.positive("radius");
      }
      const auto poly = read_region(d.at("region"));
      check_resolution(d, poly, r0);
      const double phi = d.non_negative("fraction");
      if (phi > 0.6) d.fail("fraction", "random sequential addition jams near 0.55: use at most 0.6 (then settle)");
      if (polygon_area(poly) / (r0 * r0) > 4e7) d.fail("radius", "more than 1e7 discs: check the radius");
      const int attempts = d.integer("attempts", 1);
      if (attempts > kRandomPackAttempts) d.fail("attempts", "at most 1000000 consecutive failed trials");
      PackReport rep;
      made = random_pack(poly, r0, r1, phi, d.integer("count", 0), static_cast<unsigned>(d.integer("seed", 0)),
                         attempts, &rep);
      auto fmt = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3g", v);
        return std::string(buf);
      };
      const bool short_of_fraction = phi > 0 && rep.fraction < phi;
      // A pack that drew the whole budget of trials without jamming or filling is far from its target: random
      // sequential addition jams near 0.547 for equal discs (Feder 1980; Hinrichsen, Feder & Jossang 1986).
      if (short_of_fraction && !rep.jammed && rep.trials >= kRandomPackTrials)
        d.fail("fraction",
               "the random pack reached a packing fraction of " + fmt(rep.fraction) + " after " +
                   fmt(double(rep.trials)) + " trials (the limit), not " + fmt(phi) +
                   ": random sequential addition jams near 0.547 for equal discs; ask for less, then settle");
      if (short_of_fraction && warnings && !made.empty())
        warnings->push_back(d.child_path("fraction") + ": the random pack jammed at a packing fraction of " +
                            fmt(rep.fraction) + ", not the requested " + fmt(phi) + " (" + std::to_string(attempts) +
                            " trials in a row failed): a looser pack than asked for");
    }
    if (made.empty()) d.fail("no disc fits in the region");
    const Vec2 v = d.vec2("velocity");
    const double w = d.number("angular_velocity");
    for (auto& s : made) {
      s.v = v;
      s.w = w;
      s.group = static_cast<int>(g);
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace lagfsi::dem
