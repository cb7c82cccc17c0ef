#pragma once
/// @file dem/dem_particles.hpp
/// The discs of a DEM body and their generators.
///
/// A disc of radius r is a cylinder of unit out-of-plane depth (plane problem): m = rho pi r^2 (1 m),
/// I = 1/2 m r^2 ("mass": "disc", the default; Sabatucci et al. 2013 use 2D discs). "mass": "sphere" gives the
/// discs the mass and inertia of spheres, m = 4/3 rho pi r^3, I = 2/5 m r^2, to reproduce 3D benchmarks of
/// central impacts (Chung & Ooi 2011), where the motion stays in a plane.
///
/// Generators (the body's "discs" array; their discs are appended in order, so layered beds are several
/// generators with stacked regions):
///  - {"type": "list", "discs": [[x, y, r], ...]}
///  - {"type": "hex_lattice", "region": R, "radius": r, "gap": g}: a hexagonal (triangular) lattice of pitch
///    2 r (1 + g), rows 2 r (1 + g) sqrt(3)/2 apart, the first row resting on the region's bottom, every disc
///    wholly inside the region (e.g. 300/299 discs per row and 123 rows, 36 839 discs, for 4 mm discs in
///    1.2 x 0.427 m, the bed of Sabatucci et al.);
///  - {"type": "random", "region": R, "radius": [r_min, r_max], "fraction": phi, "seed": s}: random sequential
///    addition of non-overlapping discs (radii uniform in [r_min, r_max]) until the packing fraction phi or
///    "count" discs (a loose pack; the body's "settle" stage lets it settle under gravity before t = 0).
/// Each generator may set "velocity": [vx, vy] and "angular_velocity" of its discs. Regions:
/// {"type": "rectangle", "origin": [x, y], "size": [w, h]} or {"type": "polygon", "points": [[x, y], ...]}.
#include <lagfsi/params.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lagfsi::dem {

/// One generated disc.
struct DiscSpec {
  Vec2 x = Vec2::Zero();
  double r = 0;
  Vec2 v = Vec2::Zero();
  double w = 0;
  int group = 0;  ///< the generator that made it (its index in "discs")
};

/// Per-disc properties (the positions and velocities are the model's dofs, in the same order).
struct Discs {
  std::vector<double> radius, mass, inertia;
  std::vector<Index> id;           ///< number at generation (stable through reordering)
  std::vector<std::uint8_t> mark;  ///< ruptured (Sabatucci law), or other flags for output
  std::vector<int> group;
  size_t size() const { return radius.size(); }
};

/// A hexagonal lattice of discs of radius r in a polygon (discs wholly inside), pitch 2 r (1 + gap).
std::vector<DiscSpec> hex_lattice(const std::vector<Vec2>& polygon, double r, double gap);

/// How a random pack ended (random_pack).
struct PackReport {
  double fraction = 0;  ///< the packing fraction reached (disc area / region area)
  long trials = 0;      ///< trial positions drawn
  bool jammed = false;  ///< `attempts` consecutive trials failed before the fraction or the count was reached
};

/// The largest number of trial positions a random pack draws in all (about 10 s): past it
/// generate_discs fails, since a fraction that this many trials cannot reach is one the pack cannot reach.
inline constexpr long kRandomPackTrials = 20'000'000;
/// The largest "attempts" (consecutive failed trials before the pack counts as jammed).
inline constexpr int kRandomPackAttempts = 1'000'000;

/// Random sequential addition in a polygon: radii uniform in [r_min, r_max], until the packing fraction or the
/// count is reached, `attempts` consecutive trials failed, or max_trials trials were drawn in all;
/// deterministic for a seed. `report` (if given) receives how it ended.
std::vector<DiscSpec> random_pack(const std::vector<Vec2>& polygon, double r_min, double r_max, double fraction,
                                  int count, unsigned seed, int attempts, PackReport* report = nullptr,
                                  long max_trials = kRandomPackTrials);

/// A region object (rectangle or polygon) as a polygon.
std::vector<Vec2> read_region(Params region);

/// Reads the body's "discs" array (validating each generator). A random pack that jammed below its fraction
/// adds a line to `warnings` (if given); one that used up kRandomPackTrials is an error.
std::vector<DiscSpec> generate_discs(Params discs, std::vector<std::string>* warnings = nullptr);

/// Area of a simple polygon, whether a point is inside it, and its distance to the boundary.
double polygon_area(const std::vector<Vec2>& p);
bool inside_polygon(const std::vector<Vec2>& p, const Vec2& x);
double distance_to_boundary(const std::vector<Vec2>& p, const Vec2& x);

}  // namespace lagfsi::dem
