// Benchmark (not a test): PFEM remeshing of a dam-break-like particle cloud (a perturbed block of fluid
// particles against the left wall of a tank made of two lines of wall particles). Times, best of
// `repeats`, the Delaunay triangulation alone (delaunay_triangles: range insertion + listing the faces)
// and the whole remesh() (triangulation + alpha test + wall-only removal + free surface), single thread;
// and the advected domain detection (docs/decisions/0001-advected-domain.md): the last mesh carried by the particles
// (here: the alpha mesh, with every particle then moved by up to 0.05 h) built into a PreviousDomain with its topology,
// and remesh() with it as the predicate (point location of every new element's centroid, restored boundary edges). The
// fluid's particle management on the advected mesh (merges, splits, inserts: O(n) passes over the elements in
// src/fluid) is not in it. Goal: remesh <= 2 us per particle for 1e4 - 1e5 particles.
//
// usage: bench_remesh [repeats=5] [n1 n2 ...]   (default sizes 1e4 1e5 4e5)
#include <lagfsi/meshing/previous_domain.hpp>
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
using lagfsi::bench::best_of;
using lagfsi::meshing::ParticleKind;

namespace {

struct Cloud {
  std::vector<Vec2> points;
  std::vector<ParticleKind> kind;
  std::vector<double> h;
};

// Fluid block of (2 m) x m particles with spacing h = 1/m (perturbed by up to 0.15 h), in a tank of
// width 4 and height 2 (in block heights) whose walls are two lines of particles at spacing h.
Cloud dam_break(int target) {
  const int m = std::max(4, static_cast<int>(std::sqrt(target / 2.0) * 0.94));  // walls add ~12 m
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
  const int nx = 4 * m + 1, ny = 2 * m;  // wall particles along x (bottom) and y (sides)
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

  std::printf("%10s %10s %12s %12s %10s %8s %8s %8s %12s %8s\n", "particles", "triangles", "delaunay", "remesh",
              "ratio", "kept", "alpha", "walls", "advected", "added");
  std::printf("%10s %10s %12s %12s %10s %8s %8s %8s %12s %8s\n", "", "", "[us/part]", "[us/part]", "", "", "", "",
              "[us/part]", "");
  for (int target : sizes) {
    const Cloud c = dam_break(target);
    const double n = static_cast<double>(c.points.size());
    std::size_t ntri = 0;
    const double t_del = best_of(repeats, [&] { ntri = meshing::delaunay_triangles(c.points).size(); });
    meshing::RemeshResult r;
    const double t_rem = best_of(repeats, [&] { r = meshing::remesh(c.points, c.kind, c.h, {}); });
    // The advected detection: the alpha mesh as the last step's, its particles moved by up to 0.05 h.
    std::vector<Vec2> moved = c.points;
    std::mt19937_64 rng(777);
    std::uniform_real_distribution<double> step(-0.05, 0.05);
    for (std::size_t i = 0; i < moved.size(); ++i)
      if (c.kind[i] == ParticleKind::Fluid) moved[i] += c.h[i] * Vec2(step(rng), step(rng));
    std::vector<std::uint8_t> meshed(moved.size(), 0);
    std::vector<std::pair<Index, Index>> edges;
    for (const auto& t : r.triangles)
      for (int k = 0; k < 3; ++k) {
        meshed[static_cast<std::size_t>(t[k])] = 1;
        edges.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
      }
    std::sort(edges.begin(), edges.end());
    std::vector<std::pair<Index, Index>> boundary_edges;
    for (std::size_t k = 0; k < edges.size(); ++k)
      if (!((k + 1 < edges.size() && edges[k + 1] == edges[k]) || (k > 0 && edges[k - 1] == edges[k])))
        boundary_edges.push_back(edges[k]);
    meshing::RemeshResult ra;
    const double t_adv = best_of(repeats, [&] {
      std::vector<std::array<Vec2, 3>> tris;
      tris.reserve(r.triangles.size());
      for (const auto& t : r.triangles) tris.push_back({moved[t[0]], moved[t[1]], moved[t[2]]});
      std::vector<std::array<Vec2, 2>> bnd;
      for (const auto& [a, b] : boundary_edges) bnd.push_back({moved[a], moved[b]});
      meshing::PreviousDomain previous(std::move(tris), std::move(bnd));
      previous.set_topology(meshed, boundary_edges);
      meshing::RemeshSettings s;
      s.detection = meshing::DomainDetection::Advected;
      s.previous = &previous;
      ra = meshing::remesh(moved, c.kind, c.h, s);
    });
    std::printf("%10zu %10zu %12.3f %12.3f %10.3f %8zu %8d %8d %12.3f %8d\n", c.points.size(), ntri, 1e6 * t_del / n,
                1e6 * t_rem / n, t_rem / t_del, r.triangles.size(), r.removed_alpha, r.removed_boundary_only,
                1e6 * t_adv / n, ra.added_outside);
  }
  return 0;
}
