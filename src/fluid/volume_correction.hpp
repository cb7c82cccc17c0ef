#pragma once
/// @file volume_correction.hpp (private to src/fluid)
/// The fluid's area bookkeeping (initial, reference, after remeshing, at the end of the step, left through
/// the domain box) and the volume corrections: "surface" (restore_area: a geometric move of the free surface
/// after remeshing), "source" (c_vol: a uniform source in the continuity equation) and "particle" (each
/// particle keeps its own share of the area: what a step or a remesh took from it is returned where it was
/// taken, by a local source in its continuity row, owed_rate).
#include <lagfsi/fluid/particle_cloud.hpp>
#include "fluid_common.hpp"
#include "fluid_mesh.hpp"

#include <lagfsi/params.hpp>

namespace lagfsi::fluid {

class VolumeCorrection {
 public:
  enum class Type { surface, source, particle, none };
  VolumeCorrection(const FluidConstants& c, ParticleCloud& cloud, const FluidMesh& mesh)
      : c_(c), cloud_(cloud), mesh_(mesh) {}
  /// The case's "volume_correction" and "volume_relaxation_time" (s).
  void configure(Type type, double relax_time) {
    type_ = type;
    relax_time_ = relax_time;
  }
  Type type() const { return type_; }

  /// The initial mesh's area: the reference, initial, remeshed and end-of-step areas (initialize).
  void start(double area) {
    area_ref_ = area_remesh_ = area_end_ = area_initial_ = area;
    error_filtered_ = error_filtered_step_ = 0;
  }
  /// Fluid dropped outside the domain box: `share` of the last mesh's area left with it (added up by
  /// drop_outside_domain, then rebase()).
  void add_left(double share) { area_left_ += share; }
  /// The fluid that left is gone from the reference area too, so that the correction does not make it up
  /// elsewhere.
  void rebase() { area_ref_ = area_initial_ - area_left_ + area_entered_; }
  /// Fluid that entered through an inflow (its particles' area, appended after a step): the reference grows by it.
  void add_entered(double area) {
    area_entered_ += area;
    rebase();
  }

  /// Volume correction "surface": moves the free-surface particles along the gradient of the mesh area so
  /// that the area after remeshing equals the reference area again. Particles marked in `still` (per particle, may
  /// be empty) stay: the faces of inflows and outflows, which are boundaries of the water, not free surface.
  void restore_area(const std::vector<char>& still = {});
  /// The step's mesh after remeshing has area `area`, the step is `dt` long: the "source" coefficient c_vol of
  /// the step; with "particle", the particles' shares of the area at the step's start. A retry of the step
  /// (a smaller dt) calls it again from the same state: the source's filter moves on only at set_end.
  void set_remeshed(double area, double dt);
  /// The mesh's area at the end of the step; what the step changed since the remeshing (the solve's discrete
  /// incompressibility, the wall put-backs) is added up; with "particle", what it changed at each particle
  /// is owed to it.
  void set_end(double area);

  /// "particle": what a remesh changed at each particle is owed to the particles where it changed. `before`:
  /// the particles' shares of the last step's mesh at their present positions, before the remesh, numbered
  /// as then; `present[i]`: the index now of that particle i (the survivor of its merge), -1 if it went.
  /// The change of a particle's share alone is not owed: re-triangulating the same points moves area between
  /// neighbours (an edge flip changes four shares by up to h^2 / 6 but not their sum). What is owed is the
  /// change summed over each group of changed particles connected by the new mesh (zero for flips; the
  /// area of a gap closed, of a film merged, of a sliver torn off), shared among its fluid particles in
  /// proportion to their own changes (a group of wall or ghost particles only: among them, and they hand it
  /// to the fluid, hand_owed_inward).
  void owe_remesh_change(const std::vector<double>& before, const std::vector<Index>& present);
  /// "particle": a particle whose pressure is prescribed (`fixed`, 3 per particle: p = 0 on the free surface
  /// with "dirichlet", the fractional step's) has no continuity row to return its area: it hands what it is
  /// owed to the particles with one that share an element with it (equal shares per element), once a step.
  void hand_owed_inward(const std::vector<char>& fixed);
  /// "particle" with the fractional step: a particle whose pressure is prescribed (`fixed`) gives back what
  /// it is owed by a move along the gradient of the mesh area at its position (its elements grow by what it is
  /// owed; `held`: 2 per particle, the components a wall prescribes, which do not move). What the move changes
  /// at every particle is taken from what it is owed (the sum of the owed areas and the mesh's area is kept).
  /// Before set_remeshed.
  void return_owed_by_moves(const std::vector<char>& fixed, const std::vector<char>& held);
  /// "particle": a particle with a continuity row owed less than minus its share of the area (asked to give
  /// more than its elements have: a film's or a jet's tip) keeps a debt of its share; the rest goes to the
  /// particles inside the water in proportion to their shares (summary.json "returned_through_bulk"). Once a
  /// step, after set_remeshed (whose shares it uses) and hand_owed_inward.
  void return_unpayable_through_bulk(const std::vector<char>& fixed);
  /// "particle": the local source of particle i's continuity row, the rate at which its share of the area
  /// must grow, owed_i / T (T = "volume_relaxation_time"); 0 otherwise.
  double owed_rate(Index i) const { return type_ == Type::particle ? cloud_.owed()[i] / relax_time_ : 0.0; }

  /// The uniform source of the continuity equation (0 unless "source").
  double c_vol() const { return c_vol_; }
  double area_remeshed() const { return area_remesh_; }
  double area_end() const { return area_end_; }
  /// The water at the end of the step: the mesh's area and, with "particle", the area owed to the particles
  /// in no element (a drop in flight carries the share it had when it left the mesh). Without "particle", the
  /// mesh's area.
  double water_area() const { return area_end_ + in_flight_; }
  /// Potential energy put into the fluid by the "surface" correction's moves, -sum m_i g . dx_i.
  double correction_energy() const { return correction_energy_; }
  /// summary.json's "fluid_area": initial, final, left the domain, drift without the latter, and the change
  /// split into what the steps made (change_in_steps) and the rest (change_by_remeshing: remeshing, the
  /// correction, the fluid dropped outside the domain box).
  Json summary() const;
  /// Checkpoints (state_archive.hpp; fluid_checkpoint.cpp).
  void serialize(StateArchive& ar);

 private:
  /// Whether particle i returns its own area, through its continuity row: a fluid particle whose pressure is
  /// not prescribed (`fixed`: the step's Dirichlet flags, 3 per particle).
  bool has_row(Index i, const std::vector<char>& fixed) const {
    return cloud_.kind(i) == ParticleKind::Fluid && !fixed[3 * i + 2];
  }
  const FluidConstants& c_;
  ParticleCloud& cloud_;
  const FluidMesh& mesh_;
  Type type_ = Type::surface;
  double relax_time_ = 0.1;  // s: the "source" correction closes an area error over this time
  double area_ref_ = 0, area_remesh_ = 0, area_end_ = 0, c_vol_ = 0;
  // "source": the area error after remeshing, low-pass filtered over relax_time_ / 2 (set_remeshed): the value of
  // the last finished step, and the one the step under way will commit (set_end).
  double error_filtered_ = 0, error_filtered_step_ = 0;
  double area_initial_ = 0, area_left_ = 0;  // initial mesh area; area of the fluid dropped outside the box
  double area_entered_ = 0;                  // area of the fluid an inflow added
  double correction_energy_ = 0;
  double change_in_steps_ = 0;        // the sum over the steps of their area change after remeshing
  std::vector<double> nodal_start_;   // "particle": the particles' shares of the area at the step's start
  double in_flight_ = 0;              // "particle": the area owed to particles in no element (water_area)
  double returned_through_bulk_ = 0;  // "particle": return_unpayable_through_bulk, added up
  double water_drift_max_ = 0;        // "particle": the largest |water + left - initial| / initial of the steps
};

}  // namespace lagfsi::fluid
