// Benchmark (not a test): "the practical floor" of one PFEM step for a particle cloud. A step of any
// PFEM scheme remeshes the cloud and factorizes at least one matrix on the new mesh (whose pattern
// changed, so the symbolic analysis is redone); the cheapest such matrix is a P1 pressure Laplacian with
// one unknown per particle. This program times, single thread, best of `repeats`:
//   (a) one meshing::remesh() (Delaunay + alpha test with alpha = 1.2 + wall-only removal + free surface),
//   (b) assembling the P1 Laplacian on the kept triangles: ElementPattern (CSC pattern + scatter map, built
//       anew as the mesh changes every step) + the element loop + Dirichlet p = 0 on the free-surface
//       particles by row/column elimination (a small diagonal shift keeps wall-only nodes SPD),
//   (c) one CHOLMOD factorization (symbolic + numeric) + one solve,
// on the dam-break cloud of cases/dam_break_tank at spacing h: a column L x 2L (L = 0.146) of fluid
// particles on a square lattice (i h, j h), i = 1..L/h, j = 1..2L/h, and wall particles at spacing h
// along the tank's left wall, floor and right wall (tank 4L wide, 4L high), as the case builds them.
// floor = (a) + (c) per particle (assembly of the real system is scheme-dependent and left out).
//
// usage: bench_pfem_floor [--repeats N] [--jitter f] [--csv] [h1 h2 ...]
//   h: a spacing in metres or "L/k" (default L/20 L/40 L/80); --jitter f moves each fluid particle by up
//   to f h in x and y (default 0: the exact lattice of the case at t = 0); --csv prints CSV instead.
#include <lagfsi/assembly.hpp>
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/meshing/remesh.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bench_timing.hpp"

using namespace lagfsi;
using lagfsi::bench::best_of;
using lagfsi::bench::Clock;
using lagfsi::bench::seconds;
using lagfsi::meshing::ParticleKind;

namespace {

constexpr double kL = 0.146;

struct Cloud {
  std::vector<Vec2> points;
  std::vector<ParticleKind> kind;
  std::vector<double> h;
  int walls = 0;
};

// The dam-break cloud of cases/dam_break_tank at spacing h (same construction as the fluid body: wall
// particles first along the polyline (0,4L) -> (0,0) -> (4L,0) -> (4L,4L), ceil(4L/h) intervals per
// segment, shared corners once; then the lattice of the column without the particles within h/2 of a wall).
Cloud dam_break(double h, double jitter) {
  Cloud c;
  auto add = [&c, h](const Vec2& p, ParticleKind k) {
    c.points.push_back(p);
    c.kind.push_back(k);
    c.h.push_back(h);
  };
  const std::vector<Vec2> poly = {{0, 4 * kL}, {0, 0}, {4 * kL, 0}, {4 * kL, 4 * kL}};
  for (size_t s = 0; s + 1 < poly.size(); ++s) {
    const Vec2 a = poly[s], b = poly[s + 1];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / h * (1 - 1e-12))));
    for (int k = (s == 0 ? 0 : 1); k <= n; ++k) add(a + (b - a) * (double(k) / n), ParticleKind::Wall);
  }
  c.walls = static_cast<int>(c.points.size());
  const int nx = std::max(1, static_cast<int>(std::lround(kL / h)));
  const int ny = std::max(1, static_cast<int>(std::lround(2 * kL / h)));
  const double hx = kL / nx, hy = 2 * kL / ny;
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-jitter * h, jitter * h);
  for (int j = 1; j <= ny; ++j)
    for (int i = 1; i <= nx; ++i) {
      Vec2 p(i * hx, j * hy);
      if (jitter > 0) p += Vec2(u(rng), u(rng));
      add(p, ParticleKind::Fluid);
    }
  return c;
}

// P1 Laplacian of a triangle (column-major 3 x 3): K_ij = (grad N_i . grad N_j) A.
struct Local3 {
  double k[9];
  double operator()(int i, int j) const { return k[j * 3 + i]; }
};

Local3 laplacian(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double y[3] = {b.y() - c.y(), c.y() - a.y(), a.y() - b.y()};
  const double x[3] = {c.x() - b.x(), a.x() - c.x(), b.x() - a.x()};
  const double A2 = x[2] * y[1] - x[1] * y[2];  // 2 A (positive for counter-clockwise)
  Local3 K;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) K.k[j * 3 + i] = (y[i] * y[j] + x[i] * x[j]) / (2 * A2);
  return K;
}

double parse_h(const std::string& s) {
  if (s.size() > 2 && (s[0] == 'L' || s[0] == 'l') && s[1] == '/') return kL / std::atof(s.c_str() + 2);
  return std::atof(s.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5;
  double jitter = 0;
  bool csv = false;
  std::vector<std::string> hs;
  for (int a = 1; a < argc; ++a) {
    const std::string s = argv[a];
    if (s == "--repeats" && a + 1 < argc)
      repeats = std::max(1, std::atoi(argv[++a]));
    else if (s == "--jitter" && a + 1 < argc)
      jitter = std::atof(argv[++a]);
    else if (s == "--csv")
      csv = true;
    else if (s == "-h" || s == "--help") {
      std::printf("usage: bench_pfem_floor [--repeats N] [--jitter f] [--csv] [h ... | L/k ...]\n");
      return 0;
    } else
      hs.push_back(s);
  }
  if (hs.empty()) hs = {"L/20", "L/40", "L/80"};

  if (csv)
    std::printf(
        "h,L_over_h,particles,fluid,walls,triangles,free_surface,nonzeros,remesh_us,assembly_us,"
        "pattern_us,factorization_us,solve_us,chol_us,floor_us\n");
  else {
    std::printf("bench_pfem_floor: dam-break cloud, alpha 1.2, best of %d, jitter %.2f h; times in us per particle\n",
                repeats, jitter);
    std::printf("%8s %6s %9s %9s %9s %9s | %8s %8s %8s %8s %8s %8s | %8s\n", "h", "L/h", "particles", "triangles",
                "free", "nnz", "(a)remsh", "(b)asm", "pattern", "factor", "solve", "(c)chol", "floor");
  }
  for (const std::string& hstr : hs) {
    const double h = parse_h(hstr);
    if (!(h > 0) || h > kL) {
      std::fprintf(stderr, "bench_pfem_floor: bad spacing '%s'\n", hstr.c_str());
      return 1;
    }
    const Cloud c = dam_break(h, jitter);
    const Index np = static_cast<Index>(c.points.size());
    const double n = np;

    // (a) remeshing.
    meshing::RemeshResult r;
    const double t_rem = best_of(repeats, [&](int) { r = meshing::remesh(c.points, c.kind, c.h, {1.2}); });

    // (b) pattern + Laplacian assembly + elimination of the free-surface rows and columns.
    std::vector<Index> conn;
    SparseMatrix A;
    double t_pat = 1e300;
    const double t_asm = best_of(repeats, [&](int) {
      const auto t0 = Clock::now();
      conn.resize(3 * r.triangles.size());
      for (size_t e = 0; e < r.triangles.size(); ++e)
        for (int k = 0; k < 3; ++k) conn[3 * e + k] = r.triangles[e][k];
      ElementPattern pat(conn, 3, np, 1);
      t_pat = std::min(t_pat, seconds(t0));
      A = pat.pattern();
      double* val = A.valuePtr();
      std::fill(val, val + A.nonZeros(), 0.0);
      for (Index e = 0; e < pat.num_elements(); ++e) {
        const auto& t = r.triangles[e];
        pat.add(e, laplacian(c.points[t[0]], c.points[t[1]], c.points[t[2]]), val);
      }
      // Dirichlet p = 0 on free-surface particles (and 1 on the diagonal of unconnected ones), by
      // row/column elimination; a small shift on the other diagonals for wall-only components.
      const int* op = A.outerIndexPtr();
      const int* ip = A.innerIndexPtr();
      for (Index j = 0; j < np; ++j) {
        const bool fixed_j = r.free_surface[j] || !r.connected[j];
        for (int q = op[j]; q < op[j + 1]; ++q) {
          const Index i = ip[q];
          if (i == j)
            val[q] = fixed_j ? 1.0 : val[q] + 1e-9;
          else if (fixed_j || r.free_surface[i] || !r.connected[i])
            val[q] = 0.0;
        }
      }
    });

    // (c) CHOLMOD symbolic + numeric factorization and one solve (a fresh solver each time, as the
    // pattern changes every step: the symbolic analysis is always redone).
    std::vector<std::unique_ptr<LinearSolver>> solvers;
    for (int i = 0; i < repeats; ++i) solvers.push_back(make_linear_solver("cholmod"));
    Vec b = Vec::Ones(np), x;
    for (Index i = 0; i < np; ++i)
      if (r.free_surface[i] || !r.connected[i]) b[i] = 0;
    const double t_fact = best_of(repeats, [&](int i) { solvers[i]->setup(A); });
    const double t_solve = best_of(repeats, [&](int i) { solvers[i]->solve(b, x); });
    const double t_chol = t_fact + t_solve;
    if (!x.allFinite()) {
      std::fprintf(stderr, "bench_pfem_floor: non-finite solution at h = %g\n", h);
      return 1;
    }
    const int nfree = static_cast<int>(std::count(r.free_surface.begin(), r.free_surface.end(), 1));
    const double us = 1e6 / n;
    if (csv)
      std::printf("%.8g,%.3f,%d,%d,%d,%zu,%d,%ld,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", h, kL / h, np, np - c.walls,
                  c.walls, r.triangles.size(), nfree, static_cast<long>(A.nonZeros()), us * t_rem, us * t_asm,
                  us * t_pat, us * t_fact, us * t_solve, us * t_chol, us * (t_rem + t_chol));
    else
      std::printf("%8.6f %6.1f %9d %9zu %9d %9ld | %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f | %8.3f\n", h, kL / h, np,
                  r.triangles.size(), nfree, static_cast<long>(A.nonZeros()), us * t_rem, us * t_asm, us * t_pat,
                  us * t_fact, us * t_solve, us * t_chol, us * (t_rem + t_chol));
    std::fflush(stdout);
  }
  return 0;
}
