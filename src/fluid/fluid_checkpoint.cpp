// Checkpoints of the PFEM fluid (state_archive.hpp): what each piece keeps from one step to the next. Taken
// after finalize_step; a restart reads it over the state initialize() built. The mesh is the last step's (the
// advected domain of the next remesh starts from it), the areas and energies are running sums, the step's
// data (p_scale, the boundary forces) carry over; the schemes' matrices are rebuilt at every step.
#include "fluid_model_impl.hpp"

namespace lagfsi::fluid {

void ParticleCloud::serialize(StateArchive& ar) {
  ar.section("particles");
  ar.io(kind_, hvec_, state_.t, state_.x, state_.v, state_.a, X0_, p_, owed_);
  const size_t n = kind_.size();
  if (ar.loading() && (hvec_.size() != n || static_cast<size_t>(state_.x.size()) != 2 * n ||
                       static_cast<size_t>(state_.v.size()) != 2 * n || static_cast<size_t>(state_.a.size()) != 2 * n ||
                       static_cast<size_t>(X0_.size()) != 2 * n || static_cast<size_t>(p_.size()) != n ||
                       static_cast<size_t>(owed_.size()) != n))
    throw CheckpointError("the particles' arrays differ in size");
}

void FluidMesh::serialize(StateArchive& ar) {
  ar.section("mesh");
  ar.io(tri, conn, free, connected);
}

void FluidWalls::serialize(StateArchive& ar) {
  ar.section("walls");
  ar.io(wall_crossings_, wall_snaps_, wall_releases_);
}

void Ghosts::serialize(StateArchive& ar) {
  ar.section("ghosts");
  ar.io(ghost_begin_, ghost_particles_, ghost_index_, ghost_merged_, ghost_neighbours_);
  ar.io(ghost_x_, ghost_v_, ghost_a_, ghost_force_, contact_);
}

void RemeshPipeline::serialize(StateArchive& ar) {
  ar.section("remesh");
  ar.io(domain_lo_, domain_hi_, remesh_dA_, remesh_dKE_, remesh_area_added_, remesh_area_removed_, remesh_ke_total_,
        remesh_pe_total_);
  ar.io(merged_, merged_meeting_, split_, inserted_, added_outside_, separated_, wall_removed_, kept_edges_,
        area_excess_, coarsened_);
  ar.io(wet_corners_);
  if (ar.loading())
    for (const auto& t : wet_corners_)
      for (Index i : t)
        if (i < 0 || i >= cloud_.n() || cloud_.kind(i) != ParticleKind::Wall)
          throw CheckpointError("a wet corner names a particle that is not a wall's");
}

void VolumeCorrection::serialize(StateArchive& ar) {
  ar.section("volume");
  ar.io(area_ref_, area_remesh_, area_end_, c_vol_, area_initial_, area_left_, area_entered_, correction_energy_,
        change_in_steps_);
  // The step's starting shares are not kept: set_remeshed makes them, at the next step.
  ar.io(in_flight_, water_drift_max_, returned_through_bulk_, error_filtered_);
}

void FluidEnergy::serialize(StateArchive& ar) {
  ar.section("energy");
  ar.io(gravity_work_, dissipation_, boundary_work_, boundary_force_prev_);
}

void FluidStep::serialize(StateArchive& ar) {
  ar.section("step");
  ar.io(t_new, dt, x, p_old, fixed, p_scale, boundary_force);
}

void FluidModel::serialize(StateArchive& ar) {
  ar.section("fluid " + c_.name);
  cloud_.serialize(ar);
  mesh_.serialize(ar);
  boundaries_.serialize(ar);  // the walls, then the case's boundaries
  ghosts_.serialize(ar);
  remesh_.serialize(ar);
  volume_.serialize(ar);
  energy_.serialize(ar);
  step_.serialize(ar);
  ar.section("scheme");
  scheme_->serialize(ar);
  ar.io(n_initial_, solved_once_, step_open_);
  serialize_series(ar, series_, ctx_.out_dir, c_.name);
  serialize_series(ar, wall_series_, ctx_.out_dir, c_.name + "_walls");
}

}  // namespace lagfsi::fluid
