#pragma once
/// @file fluid_model.hpp (private to src/fluid)
/// The PFEM fluid model shared by its schemes: particles, walls, remeshing, output and probes live in
/// fluid_model.cpp; each scheme (monolithic_pspg in fluid_model.cpp, fractional_step in fractional_step.cpp)
/// implements one step on the remeshed cloud.
#include <lagfsi/assembly.hpp>
#include <lagfsi/case.hpp>
#include <lagfsi/error.hpp>
#include <lagfsi/fluid_element.hpp>
#include <lagfsi/interface.hpp>
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/meshing/previous_domain.hpp>
#include <lagfsi/meshing/primitives.hpp>
#include <lagfsi/meshing/remesh.hpp>
#include <lagfsi/time_function.hpp>
#include <lagfsi/time_integrator.hpp>
#include <lagfsi/vtk_output.hpp>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <cstdlib>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

namespace lagfsi::fluid_detail {

using meshing::ParticleKind;
using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// A rigid wall: a polyline of particles (PFEM mode) or a line of constraints (fixed-connectivity mode),
/// optionally moving: x(t) = X + value * f(t) (or value * int f for a prescribed velocity).
struct Wall {
  std::string name;
  std::vector<Vec2> polyline;
  bool slip = false;
  Vec2 value = Vec2::Zero();
  std::shared_ptr<TimeFunction> fn;
  bool velocity = false;
  std::vector<Index> particles;  // PFEM mode: its particles in polyline order
  std::vector<int> fluid_side;   // per segment: +1 / -1 the initial fluid lies on the side of
                                 // perp(b - a) / of its opposite, 0 on both or neither (keep_inside_walls)
  Vec2 offset(double t) const {
    if (!fn) return Vec2::Zero();
    return value * (velocity ? fn->integral(t) : fn->value(t));
  }
  /// Prescribed velocity and acceleration (central differences of the offset in time; exact to round-off
  /// for smooth functions, the mean slope across a kink of a table).
  Vec2 velocity_at(double t) const {
    if (!fn) return Vec2::Zero();
    const double d = 1e-6;
    return (offset(t + d) - offset(t - d)) / (2 * d);
  }
  Vec2 acceleration_at(double t) const {
    if (!fn) return Vec2::Zero();
    const double d = 1e-4;
    return (offset(t + d) - 2.0 * offset(t) + offset(t - d)) / (d * d);
  }
};

class FluidModel final : public PhysicsModel, public InterfaceFluid {
 public:
  FluidModel(Params body, const CaseContext& ctx);
  std::string name() const override { return name_; }
  std::string type() const override { return "fluid"; }
  Index num_nodes() const override { return static_cast<Index>(kind_.size()); }
  Index num_elements() const override { return static_cast<Index>(tri_.size()); }
  double fluid_area() const override { return area_end_; }
  double fluid_area_remeshed() const override { return area_remesh_; }
  /// The fluid area (initial mesh, now, of the fluid dropped outside the domain box, and the drift without
  /// the latter: the scheme's own) and the particles put back inside a wall (keep_inside_walls).
  Json summary() const override;

  void initialize() override;
  void predict(double t_new, double dt) override;
  IterationReport solve_iteration() override;
  void finalize_step() override;
  void write_output(double t) override;
  std::unique_ptr<Probe> make_probe(Params p) override;

  // InterfaceFluid (interface.hpp): ghost particles of a structure's wet boundary.
  int add_ghosts(const std::vector<Vec2>& points, const std::vector<std::pair<Index, Index>>& adjacent) override;
  bool in_contact() const override { return contact_; }
  void set_ghost_motion(const Vec& x, const Vec& v, const Vec& a) override;
  void restart_step() override { start_iterations(); }
  Vec ghost_forces() const override { return ghost_force_; }

  // Read access for probes.
  Index n() const { return static_cast<Index>(kind_.size()); }
  Vec2 pos(Index i) const { return state_.x.segment<2>(2 * i); }
  Vec2 vel(Index i) const { return state_.v.segment<2>(2 * i); }
  double pressure(Index i) const { return p_[i]; }
  bool is_fluid(Index i) const { return kind_[i] == ParticleKind::Fluid; }
  bool is_connected(Index i) const { return connected_[i] != 0; }
  double spacing() const { return h_; }
  const std::vector<std::array<Index, 3>>& triangles() const { return tri_; }
  double kinetic_energy() const;
  /// Potential energy of gravity over the current mesh, -rho integral of g . x dA (exact on linear triangles:
  /// rho A_e g . centroid), zero at the origin. Unlike gravity_work (summed over the steps with each step's
  /// lumped masses) it depends only on the present fluid: KE + PE is the energy balance of a remeshed flow.
  double potential_energy() const;
  /// Work of gravity on the fluid and viscous dissipation since the start (account_energy(); summed only
  /// when a gravity_work or viscous_dissipation probe exists).
  double gravity_work() const { return gravity_work_; }
  double viscous_dissipation() const { return dissipation_; }
  /// Potential energy put into the fluid by the "surface" volume correction's moves, -sum m_i g . dx_i.
  double correction_energy() const { return correction_energy_; }
  double area_end() const { return area_end_; }
  /// Work done on the fluid by moving walls and by the structure's ghost particles since the start,
  /// sum over steps of F . dx at the prescribed particles (F the reaction the boundary applies, the mean of
  /// the step's start and end values; summed when an energy probe asks for it).
  double boundary_work() const { return boundary_work_; }
  /// The energy balance: KE + PE + viscous dissipation - boundary work. Constant for an exact discretization;
  /// its drift is the numerical energy (remeshing, time integration).
  double total_energy() const { return kinetic_energy() + potential_energy() + dissipation_ - boundary_work_; }
  double remesh_area_change() const override { return remesh_dA_; }
  double remesh_kinetic_energy_change() const override { return remesh_dKE_; }

 private:
  void build_particles(Params b);
  /// Delaunay + domain detection of the present cloud: the alpha shape, or (advected / level set) the
  /// previous domain `previous` as predicate; then the meniscus, flat-element and structure-crossing filters.
  void remesh_now(const meshing::PreviousDomain* previous = nullptr);
  /// The whole remesh of a step: particles leaving the domain box, particle management, the new mesh, the
  /// volume correction; measures what it changed (remesh_dA_, remesh_dKE_).
  void remesh_step();
  /// The mesh of the last step at the particles' present positions, as the predicate of the next domain.
  meshing::PreviousDomain advected_domain() const;
  /// Conservative particle management on the advected mesh (particle_management.cpp): close fluid pairs are
  /// merged (mass-weighted state; on the free surface at the position that keeps the boundary's area), long
  /// free-surface edges are split at their midpoints and large elements get a particle at their centroid
  /// (state interpolated on the mesh). Keeps tri_ consistent with the cloud. Returns true if it changed it.
  /// `meshed` and `boundary_edges` receive the previous mesh's topology in the new numbering (the particles
  /// it used, inserted ones included; its boundary edges, through merges and splits).
  bool manage_particles(std::vector<std::uint8_t>& meshed, std::vector<std::pair<Index, Index>>& boundary_edges);
  /// The boundary of the mesh tri_ as chains: next[i] / prev[i] the particle after / before i along a
  /// boundary edge (directed as in its element), -1 if none; pinched where two boundary edges leave one
  /// particle (two surfaces touching at it).
  struct BoundaryChains {
    std::vector<Index> next, prev;
    std::vector<char> pinched;
  };
  BoundaryChains boundary_chains() const;
  double mesh_area() const;
  /// Walls, then ghosts, come first in the cloud: the number of those leading non-fluid particles.
  Index n_boundary_particles() const;
  bool remove_close_particles();
  /// Removes the flagged particles (fluid only), compacting every per-particle array; the elements of tri_
  /// that use a removed particle go, the others are renumbered.
  bool drop_particles(const std::vector<char>& drop);
  std::vector<Index> renumber_;  // the last drop_particles: old index -> new index, -1 if dropped
  /// Appends a fluid particle with the given state (an inserted particle: X0 = x).
  void append_particle(const Vec2& x, const Vec2& v, const Vec2& a, double p, double h);
  /// Removes the fluid particles outside the domain box; throws SolverError when none is left.
  bool drop_outside_domain();
  /// free_ and connected_ from tri_: particles of edges used by one element, unless both ends are on a wall
  /// (`on_wall`); only Fluid particles are free surface.
  void mark_free_surface(const std::vector<char>& on_wall);
  bool insert_particles();
  double element_area(const Vec& x, Index e) const;
  /// The element kernel's input for element e at positions x (also its geometry), velocities v,
  /// accelerations a, and the integrator's d a/dx = c_m, d v/dx = c_c.
  PspgElementInput element_input(Index e, const Vec& x, const Vec& v, const Vec& a, double c_m, double c_c) const;
  void set_dirichlet();
  /// Adds the step's gravity work and viscous dissipation (before the state is updated).
  void account_energy();
  /// The step's first iterate (after remeshing, or again when a coupling re-solves the step): pressures
  /// of the last step, positions moved with the last velocities, walls and ghosts at their prescribed places.
  void start_iterations();
  /// Ghost particle g's index in the cloud (a wall particle's when merged with one).
  bool is_ghost(Index i) const { return i >= ghost_begin_ && i < ghost_begin_ + ghost_particles_; }
  /// Ghost velocities and accelerations into v and a (the prescribed motion of the step).
  void set_ghost_rates(Vec& v, Vec& a) const;
  /// An element with two ghost particles that are not neighbours along the structure crosses it.
  bool crosses_structure(Index e) const;
  /// Velocity and acceleration of the moving walls' particles at time t (their prescribed motion).
  void set_wall_motion(double t, Vec& v, Vec& a) const;
  /// Slip walls in PFEM mode: the elements that touch a slip-wall particle carry no viscous stress, so the
  /// wall transmits no shear (the free-slip condition, applied over the first layer of elements); the
  /// normal velocity is still stopped by the wall particles' positions.
  bool inviscid_element(Index e) const {
    for (Index i : tri_[e])
      if (i < static_cast<Index>(slip_particle_.size()) && slip_particle_[i]) return true;
    return false;
  }
  /// Element e has two or three particles with prescribed motion, one of them a ghost: a structure's boundary
  /// sliding past a wall or another part of it (a gate's tip over the floor). Such an element may turn over
  /// within a step without the flow being wrong; an element between walls alone that turns over is a failed
  /// step, as before (retried with dt/2).
  bool moving_boundary_pair(Index e) const {
    int prescribed = 0;
    bool ghost = false;
    for (Index i : tri_[e]) {
      prescribed += kind_[i] != ParticleKind::Fluid;
      ghost = ghost || is_ghost(i);
    }
    return prescribed >= 2 && ghost;
  }
  /// Flags of the particles of the step's elements (tri_) that have a particle i with pred(i).
  std::vector<char> in_element_with(const std::function<bool(Index)>& pred) const;
  /// Particles of an element with an interior (non-free-surface) fluid particle: the wet side of the mesh.
  std::vector<char> beside_interior_fluid() const;
  /// Volume correction "surface": moves the free-surface particles along the gradient of the mesh area so
  /// that the area after remeshing equals the reference area again (fluid_model.cpp).
  void restore_area();
  /// Fluid particles whose step crossed a wall segment go back to its fluid side (fluid_model.cpp).
  void keep_inside_walls(const Vec& x_start);
  /// One Newton iteration of the monolithic PSPG scheme (fluid_model.cpp).
  IterationReport newton_iteration();
  /// The whole step of the fractional-step scheme (fractional_step.cpp).
  IterationReport fractional_step();
  /// Fractional step: the viscous predictor is implicit (the automatic choice: when the explicit one would
  /// exceed its stability limit dt <= rho h_min^2 / (8 mu), h_min = 0.3 h).
  bool viscous_implicit() const;
  /// Factorizes a matrix of the fractional step (time counted as factorization); a failure names the body
  /// and `what`.
  void factorize_step_matrix(LinearSolver& solver, const SparseMatrix& A, const char* what);

  std::string name_;
  CaseContext ctx_;
  double rho_ = 1000, mu_ = 1e-3, h_ = 0.01, alpha_ = 1.2;
  bool remesh_ = true, lumped_ = true, p_free_dirichlet_ = true;
  std::string tau_type_ = "automatic";
  double tau_U_ = 1.0;
  std::string volume_correction_ = "surface";  // surface | source | none
  meshing::DomainDetection detection_ = meshing::DomainDetection::Alpha;
  double separation_alpha_ = 2.5;  // advected / level set: an inside element is torn off when R > this h
  double level_set_band_ = 0.25;   // level set: outside elements within this h of the previous boundary
  double split_factor_ = 1.6;      // advected / level set: split free-surface edges longer than this h
  // Remeshing's effect per step (log.csv) and over the run (summary.json).
  double remesh_dA_ = 0, remesh_dKE_ = 0;
  double remesh_area_added_ = 0, remesh_area_removed_ = 0, remesh_ke_total_ = 0, remesh_pe_total_ = 0;
  long merged_ = 0, split_ = 0, inserted_ = 0, added_outside_ = 0, separated_ = 0, wall_removed_ = 0;
  double boundary_work_ = 0;
  std::vector<std::array<Vec2, 3>> region_triangles_;  // the fluid regions' elements (the initial domain)
  Index n_initial_ = 0;
  Vec boundary_force_, boundary_force_prev_;  // per non-fluid particle (walls, ghosts: stable indices), 2 each
  double relax_time_ = 0.1;      // s: the "source" correction closes an area error over this time
  double tol_ = 1e-4;
  int refactor_every_ = 0;       // 0: one factorization per step (the matrix barely changes within a
                                 // step); k >= 1: refactorized every k iterations (1: Newton)
  int iter_in_step_ = 0;           // monolithic: iterations of the step (all coupling passes)
  bool step_factorized_ = false;   // fractional step: the step's matrices are factorized (reused by re-solves)
  double close_fraction_ = 0.3;  // remove a fluid particle closer than this * h to another particle
  double flat_fraction_ = 0.01;  // drop elements with area below this * h^2
  double insert_factor_ = 1.0;   // insert a particle at the centroid of elements larger than this * h^2
  double bulk_ = 2.2e9;          // bulk modulus of the slight compressibility (0: incompressible)
  std::string solver_type_ = "klu";
  std::string scheme_ = "monolithic_pspg";
  std::string viscous_step_ = "automatic";  // fractional step: automatic | explicit | implicit

  std::vector<ParticleKind> kind_;
  std::vector<Wall> walls_;
  std::vector<char> slip_particle_;
  double domain_margin_ = 0.1;       // the domain box: walls and initial fluid, enlarged by this * larger side
  Vec2 domain_lo_ = Vec2::Constant(1.0), domain_hi_ = Vec2::Constant(-1.0);  // empty: fixed connectivity  // per wall particle (wall particles come first and are never removed)
  std::vector<double> hvec_;
  Vec X0_;                          // initial positions (walls move relative to these)
  KinematicState state_;            // x, v, a of all particles
  Vec p_, p_old_;
  std::unique_ptr<TimeIntegrator> integrator_;
  std::unique_ptr<LinearSolver> solver_;

  std::vector<std::array<Index, 3>> tri_;
  std::vector<Index> conn_;
  std::vector<std::uint8_t> free_, connected_;
  std::vector<char> fixed_;         // per dof (3 per particle)
  std::vector<std::pair<Index, int>> slip_;  // fixed-connectivity mode: (particle, component) constrained
  ElementPattern pattern_;
  SparseMatrix J_;
  double area_ref_ = 0, area_remesh_ = 0, area_end_ = 0, c_vol_ = 0;
  double area_initial_ = 0, area_left_ = 0;  // initial mesh area; area of the fluid dropped outside the box
  long wall_crossings_ = 0;         // fluid particles put back inside a wall (keep_inside_walls)
  bool retry_inverted_ = true;      // fractional step: an element inverted within the step fails it (retry)
  long inverted_in_step_ = 0, inverted_kept_ = 0;  // fractional step: inverted elements in the last solve /
                                                   // in the accepted steps ("inverted_elements": "remesh")
  double p_scale_ = 1;

  Vec x_;                           // iterate of x_{n+1}
  double t_new_ = 0, dt_ = 0;
  double last_dx_ = 0, last_dp_ = 0, prev_dx_ = 0;
  bool solved_once_ = false;
  bool step_open_ = false;          // predict called and the step not finalized yet (a retry if predicted again)

  // Fractional step: the pressure Poisson matrix and the implicit viscous predictor's matrix (both one dof
  // per particle, one pattern) on the step's mesh; the step's new velocities.
  std::unique_ptr<LinearSolver> viscous_solver_;
  ElementPattern poisson_pattern_;
  SparseMatrix poisson_, viscous_, viscous_stiffness_;
  Vec v_new_;
  std::unique_ptr<PvdSeries> series_, wall_series_;

  // Ghost particles (interface.hpp): particles ghost_begin_ .. + ghost_particles_ (after the walls, before
  // the fluid, so their indices never change); ghost_index_[g] is ghost g's particle (a wall particle when
  // merged); the step's prescribed motion and the forces on them.
  Index ghost_begin_ = 0, ghost_particles_ = 0;
  std::vector<Index> ghost_index_;
  std::vector<char> ghost_merged_;
  std::vector<std::vector<Index>> ghost_neighbours_;  // per ghost particle (local), neighbouring ghost particles
  Vec ghost_x_, ghost_v_, ghost_a_, ghost_force_;
  bool contact_ = false;
  double gravity_work_ = 0, dissipation_ = 0, correction_energy_ = 0;
  bool energy_probes_ = false;  // account_energy() only for runs that probe it
};

}  // namespace lagfsi::fluid_detail
