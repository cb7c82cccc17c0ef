// Benchmark (not a test): one Newton iteration of the positional solid on a T10 mesh of about 50 000
// unknowns, split into residual + Hessian assembly, the linear solver's set-up (CHOLMOD factorization, or
// the algebraic multigrid of CG + BoomerAMG with "petsc") and solve, with 1 and 2 threads. Prints a table
// and the ratio assembly / set-up (goal: <= 0.25).
//
// usage: bench_solid [target_dofs=50000] [repeats=5] [cholmod|petsc|mumps] ["PETSc options"]
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/meshing/primitives.hpp>
#include <lagfsi/solid/solid.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench_timing.hpp"

#ifdef LAGFSI_HAVE_OPENMP
#include <omp.h>
#endif

using namespace lagfsi;
using lagfsi::bench::best_of;
using lagfsi::bench::Clock;

int main(int argc, char** argv) {
  const int target = argc > 1 ? std::atoi(argv[1]) : 50000;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
  LinearSolverSettings settings;
  settings.type = argc > 3 ? argv[3] : "cholmod";
  settings.kind = SystemKind::elasticity;
  settings.block_size = 2;
  // A 4:1 strip meshed with structured T10: nodes = (3 nx + 1)(3 ny + 1), dofs = 2 nodes.
  const int ny = std::max(1, static_cast<int>(std::sqrt(target / 2.0 / 4.0) / 3.0));
  const int nx = 4 * ny;
  TriMesh mesh = meshing::elevate(meshing::mesh_rectangle_structured(0, 0, 4, 1, nx, ny, "crossed"), 3);
  auto mat = make_solid_material("svk", 1e7, 0.3, 1000, PlaneHypothesis::PlaneStrain);
  SolidBody body(std::move(mesh), std::move(mat), 1.0);
  const Index nd = body.num_dofs();
  // A deformed state: bending-like field.
  Vec x = body.reference_positions();
  for (Index i = 0; i < body.num_nodes(); ++i) {
    const double X = x[2 * i], Y = x[2 * i + 1];
    x[2 * i] += 0.01 * Y * X;
    x[2 * i + 1] += 0.02 * X * X;
  }
  SparseMatrix K = body.pattern();
  Vec f;
  // Tangent + a mass term so the matrix is SPD (as in a dynamic step); fixed left edge left out
  // of the timing (a diagonal shift keeps the matrix SPD without Dirichlet rows).
  body.internal_force(x, f, &K);
  SparseMatrix H = K;
  H += body.mass() * 1e4;
  Vec b = Vec::Ones(nd), sol;

  std::printf("bench_solid: T10 strip, %d elements, %d nodes, %d unknowns, %ld nonzeros\n", body.mesh().num_elements(),
              body.num_nodes(), nd, static_cast<long>(H.nonZeros()));
  if (argc > 4) settings.options = argv[4];
  auto solver = make_linear_solver(settings);
  solver->set_coordinates(body.reference_positions());
  solver->setup(H);  // symbolic analysis once (reused for the whole run, as in a real step)
  const double t_fact = best_of(repeats, [&] { solver->setup(H); });
  const double t_solve = best_of(repeats, [&] { solver->solve(b, sol); });
  std::printf("solver %s: %d iterations, relative residual %.2e\n", solver->report().method.c_str(),
              solver->report().iterations, solver->report().residual);
  std::printf("%8s %14s %14s %14s %10s\n", "threads", "assembly [s]", "set-up [s]", "solve [s]", "asm/set-up");
  int max_threads = 1;
#ifdef LAGFSI_HAVE_OPENMP
  max_threads = std::min(2, omp_get_num_procs());
#endif
  for (int th = 1; th <= max_threads; ++th) {
#ifdef LAGFSI_HAVE_OPENMP
    omp_set_num_threads(th);
#endif
    const double t_asm = best_of(repeats, [&] { body.internal_force(x, f, &K); });
    std::printf("%8d %14.4f %14.4f %14.4f %10.3f\n", th, t_asm, t_fact, t_solve, t_asm / t_fact);
  }
  return 0;
}
