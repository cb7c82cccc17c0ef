#pragma once
/// @file fluid_scheme.hpp (private to src/fluid)
/// A time-stepping scheme of the PFEM fluid on the step's (remeshed) mesh, chosen once from
/// /bodies/i/scheme/type: "monolithic_pspg" (pspg_scheme.cpp: Newton on the stabilized position-pressure
/// system) or "fractional_step" (fractional_step.cpp: a pressure-correction step). Each owns its matrices,
/// patterns and linear solvers; the model calls, per step, begin_step (a new mesh), restart (the first
/// iterate, again for each coupling pass), iterate until converged, and end_step.
#include <lagfsi/fluid/particle_cloud.hpp>
#include "fluid_boundaries.hpp"
#include "fluid_common.hpp"
#include "fluid_mesh.hpp"
#include "ghosts.hpp"
#include "volume_correction.hpp"

#include <lagfsi/assembly.hpp>
#include <lagfsi/fluid/fluid_element.hpp>
#include <lagfsi/model.hpp>
#include <lagfsi/mpi_run.hpp>
#include <lagfsi/time_integrator.hpp>

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace lagfsi::fluid {

/// The particles whose rows this MPI process fills when the element assembly is divided among the processes (a
/// distributed solver over several processes, mpi_run.hpp: PETSc's default split, whole particles); all of them
/// otherwise. A process assembles the elements with a particle of its own, and the per-particle sums every process
/// needs whole are combined: each particle's entries from the process that owns it (the same bits everywhere).
class ProcessRows {
 public:
  /// For a mesh of np particles, solved by a distributed solver or not.
  void set(bool distributed, Index np) {
    split_ = distributed && mpi_run::size() > 1;
    own_ = split_ ? mpi_run::owned_blocks(np) : std::pair<Index, Index>{0, np};
  }
  bool split() const { return split_; }
  /// Particle i's rows are this process's.
  bool own(Index i) const { return i >= own_.first && i < own_.second; }
  /// The element of particles t is this process's to assemble: one of them has its rows here (every element
  /// unless split).
  bool mine(const std::array<Index, 3>& t) const { return !split_ || own(t[0]) || own(t[1]) || own(t[2]); }
  /// The matrix pattern of the elements `tri` (connectivity `conn`, np particles, dpn unknowns each) that this
  /// process assembles (the whole mesh's unless split) into `pattern`, its matrix (zeros) handed to `matrix`. The
  /// last mesh's pattern and matrix are let go first, so that the old and the new never coexist.
  void renew_pattern(ElementPattern& pattern, SparseMatrix& matrix, const std::vector<std::array<Index, 3>>& tri,
                     const std::vector<Index>& conn, Index np, int dpn) const {
    SparseMatrix().swap(matrix);
    pattern = ElementPattern();
    // The fluid's element loops add into per-thread copies (parallel_sum.hpp): no colours.
    constexpr auto none = ElementPattern::Colouring::none;
    if (!split_) {
      pattern = ElementPattern(conn, 3, np, dpn, none);
    } else {
      std::vector<char> keep(tri.size());
      for (size_t e = 0; e < tri.size(); ++e) keep[e] = mine(tri[e]) ? 1 : 0;
      pattern = ElementPattern(conn, 3, np, dpn, keep, none);
    }
    pattern.take_pattern(matrix);
  }
  /// A per-particle array (`per` values a particle) summed by each process over its elements, made whole on every
  /// process: each particle's entries kept where its rows are, zeroed elsewhere, then combined.
  void combine(Vec& a, int per) const {
    if (!split_) return;
    for (Index i = 0; i < a.size() / per; ++i)
      if (!own(i)) a.segment(per * i, per).setZero();
    mpi_run::combine_disjoint(a.data(), static_cast<Index>(a.size()));
  }

 private:
  bool split_ = false;
  std::pair<Index, Index> own_{0, 0};
};

/// The floor of FluidStep::p_scale (Pa): at it, the state gave no pressure scale (water at rest, no gravity, no
/// initial pressure).
inline constexpr double kNoPressureScale = 1e-12;

/// The step's data shared by the model and its scheme.
struct FluidStep {
  double t_new = 0, dt = 0;
  Vec x;                    // iterate of x_{n+1}
  Vec p_old;                // pressures at the start of the step
  std::vector<char> fixed;  // per dof (3 per particle: x, y, p): prescribed (FluidModel::set_dirichlet)
  double p_scale = 1;       // pressure scale of the convergence test
  bool energy = false;      // an energy probe (the boundary work) or a wall_force probe asks for the walls'
                            // and ghosts' forces: the schemes set boundary_force
  Vec boundary_force;       // per non-fluid particle (walls, ghosts: stable indices), 2 each: the force it
                            // applies to the fluid in the step's solve
  Vec constraint_force;     // per prescribed component (FluidBoundaries::constraints): the force the wall applies
                            // along its component
  /// Checkpoints (state_archive.hpp; fluid_checkpoint.cpp).
  void serialize(StateArchive& ar);
};

/// The pieces of the fluid a scheme works on (owned by the model).
struct FluidParts {
  const FluidConstants& c;
  ParticleCloud& cloud;
  FluidMesh& mesh;
  const FluidBoundaries& boundaries;  ///< the step's prescribed components: the walls' and the case's boundaries'
  Ghosts& ghosts;
  const VolumeCorrection& volume;
  FluidStep& step;
  PhaseTimes& times;
};

class FluidScheme {
 public:
  virtual ~FluidScheme() = default;
  /// The free-surface pressure: prescribed (p = 0: FluidModel::set_dirichlet; the fractional step's only one),
  /// or unknown, traction-free weakly (natural) or with the Robin condition of the element (fluid_element.hpp).
  virtual FreeSurfacePressure free_surface_pressure() const { return FreeSurfacePressure::dirichlet; }
  /// Whether it solves particles on inclined walls in their walls' frames (particle_frames.hpp); without it
  /// the walls held by constraints must be horizontal or vertical.
  virtual bool wall_frames() const { return false; }
  /// A new step on a new mesh (predict, after remeshing, the Dirichlet flags set): patterns, matrices and
  /// the time integrator's start.
  virtual void begin_step() = 0;
  /// The step's iterations start (again when a coupling re-solves the step).
  virtual void restart() {}
  /// One iteration (the monolithic scheme) or the whole step (the fractional step).
  virtual IterationReport iterate() = 0;
  /// The converged step into the particles' state (x, v, a).
  virtual void end_step() = 0;
  /// The step's velocity for the viscous dissipation (FluidEnergy::account, before end_step).
  ///
  /// The fractional step's symplectic Euler (u^{n+1} from the projection, x^{n+1} = x^n + dt u^{n+1}) is not
  /// taken through the time-integrator contract: its velocity update is the implicit viscous predictor and
  /// the pressure projection (a Poisson solve on the step's mesh), not M_L^{-1} times a force at known
  /// positions as the explicit member needs, and its positions use the end-of-step velocity, which the
  /// contract's members (Newmark family, central difference) would give only through a different update order
  /// (results not bit-identical). It stays the scheme's own two lines (fractional_step.cpp).
  virtual Vec step_velocity() const = 0;
  /// The linear solvers' records for summary.json (solver_summary), by the system they solve.
  virtual Json linear_solvers() const = 0;
  /// Elements inverted within accepted steps (the fractional step with "inverted_elements": "remesh").
  virtual long inverted_kept() const { return 0; }
  /// Checkpoints: what the scheme keeps from step to step (counters; its matrices are rebuilt every step).
  virtual void serialize(StateArchive&) {}

  /// The PSPG element kernel's input for element e at positions x (also its geometry), velocities v,
  /// accelerations a, and the integrator's d a/dx = c_m, d v/dx = c_c (pspg_scheme.cpp). The monolithic
  /// scheme's tau and mass; the initial acceleration of both schemes uses it (with the defaults for the
  /// fractional step).
  PspgElementInput element_input(Index e, const Vec& x, const Vec& v, const Vec& a, double c_m, double c_c) const;

 protected:
  explicit FluidScheme(const FluidParts& f) : f_(f) {}
  FluidParts f_;
  double tau_U_ = 0;  // the PSPG kernel's tau (0: automatic) and mass
  bool lumped_ = true;
  std::vector<unsigned char> robin_edges_;  // per element: its free-surface edges (bit k: edge k, k+1), or empty
  double robin_factor_ = 0;                 // f of the free surface's Robin term (fluid_element.hpp)
};

/// The schemes (pspg_scheme.cpp, fractional_step.cpp). The integrator is the analysis' (Newmark or
/// generalized-alpha); the fractional step does not use one.
std::unique_ptr<FluidScheme> make_pspg_scheme(const FluidParts& f, const PspgSettings& s,
                                              std::unique_ptr<TimeIntegrator> integrator);
std::unique_ptr<FluidScheme> make_fractional_step(const FluidParts& f, const FractionalStepSettings& s);

}  // namespace lagfsi::fluid
