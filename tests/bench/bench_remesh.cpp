// Benchmark (not a test): PFEM remeshing of a dam-break-like particle cloud (a perturbed block of fluid
// particles against the left wall of a tank made of two lines of wall particles). Times, best of
// `repeats`, the Delaunay triangulation alone (delaunay_triangles: range insertion + listing the faces)
// and the whole remesh() (triangulation + alpha test + wall-only removal + free surface), single thread.
// Goal: remesh <= 2 us per particle for 1e4 - 1e5 particles.
//
// usage: bench_remesh [repeats=5] [n1 n2 ...]   (default sizes 1e4 1e5 4e5)
#include <lagfsi/meshing/remesh.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "bench_timing.hpp"

using namespace lagfsi;
using lagfsi::meshing::ParticleKind;
using lagfsi::bench::best_of;

namespace {


struct Cloud {
  std::vector<Vec2> points;
  std::vector<ParticleKind> kind;
  std::vector<double> h;
};

// Fluid block of (2 m) x m particles with spacing h = 1/m (perturbed by up to 0.15 h), in a tank of
// width 4 and height 2 (in block heights) whose walls are two lines of particles at spacing h.
Cloud dam_break(int target) {
  const int m = std::max(4, static_cast<int>(std::sqrt(target / 2.0) * 0.94));   // walls add ~12 m
  const double h = 1.0 / m;
  Cloud c;
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> jitter(-0.15 * h, 0.15 * h);
  auto add = [&c, h](double x, double y, ParticleKind k) {
    c.points.emplace_back(x, y);
    c.kind.push_back(k);
    c.h.push_back(h);
  };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < 2 * m; ++i) {
      const double jx = jitter(rng), jy = jitter(rng);
      add((i + 1) * h + jx, (j + 1) * h + jy, ParticleKind::Fluid);
    }
  const int nx = 4 * m + 1, ny = 2 * m;   // wall particles along x (bottom) and y (sides)
  for (int layer = 0; layer < 2; ++layer) {
    for (int i = -layer; i <= nx + layer; ++i) add(i * h, -layer * h, ParticleKind::Wall);
    for (int j = 1; j <= ny; ++j) {
      add(-layer * h, j * h, ParticleKind::Wall);
      add((nx + layer) * h, j * h, ParticleKind::Wall);
    }
  }
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<int> sizes;
  for (int a = 2; a < argc; ++a) sizes.push_back(std::atoi(argv[a]));
  if (sizes.empty()) sizes = {10000, 100000, 400000};

  std::printf("%10s %10s %12s %12s %10s %8s %8s %8s\n", "particles", "triangles", "delaunay", "remesh",
              "ratio", "kept", "alpha", "walls");
  std::printf("%10s %10s %12s %12s %10s %8s %8s %8s\n", "", "", "[us/part]", "[us/part]", "", "", "", "");
  for (int target : sizes) {
    const Cloud c = dam_break(target);
    const double n = static_cast<double>(c.points.size());
    std::size_t ntri = 0;
    const double t_del = best_of(repeats, [&] { ntri = meshing::delaunay_triangles(c.points).size(); });
    meshing::RemeshResult r;
    const double t_rem = best_of(repeats, [&] { r = meshing::remesh(c.points, c.kind, c.h, {}); });
    std::printf("%10zu %10zu %12.3f %12.3f %10.3f %8zu %8d %8d\n", c.points.size(), ntri, 1e6 * t_del / n,
                1e6 * t_rem / n, t_rem / t_del, r.triangles.size(), r.removed_alpha, r.removed_boundary_only);
  }
  return 0;
}
