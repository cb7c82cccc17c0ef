// Checkpoints of a DEM body (state_archive.hpp, src/dem/include/lagfsi/dem/dem_model.hpp): everything a step changes
// and the next one reads. Taken after finalize_step; a restart builds the body from the case, runs initialize() (the
// settling stage too, which removes the same walls) and reads this over it.
//
//  - the discs in their current order (a rebuild reorders them): radius, mass, inertia, id, mark, group, the
//    id -> index map, the dofs (x, v, a, t), the inverse masses and the last force evaluation;
//  - the lists as built, not rebuilt: a rebuild at the restart would reorder the discs and the pairs, and with
//    them the order of every force sum and the step at which the next rebuild comes (the run would differ in the
//    last digits); so the pair list (pairs, CSR rows, incidences), the tangential spring of each pair, the pair
//    forces (the contacts and max_contact_force probes read them), rupture flags and rolling torques, the wall
//    list with its histories and forces, and the positions and wall offsets of the last build (the skin test);
//    the cell grid itself is rebuilt from scratch at every rebuild and keeps nothing;
//  - the walls' offsets (their number is checked: the case gives the same walls);
//  - the blast's exposure (with "exposure_every" > 1 the last update's loaded lengths are used until the next
//    one), its call counter and distance order, and the blast forces of the last evaluation;
//  - the energy sums (elastic, dissipated, blast work, the initial energy; the energy guard's wall work, reference
//    and scale), the ground level of the crater;
//  - the counters and timings of summary.json (sub-steps, rebuilds, force / rebuild / blast times, wall time);
//  - the output series (the .vtp of the discs and of the walls).
#include "dem_body.hpp"
#include "dem_output.hpp"

#include <lagfsi/dem/dem_model.hpp>

namespace lagfsi {

namespace dem {

void Blast::serialize(StateArchive& ar) {
  ar.section("blast");
  ar.io(calls_, exposed_, order_, order_valid_);
}

void DemWriter::serialize(StateArchive& ar, const std::string& name) {
  serialize_series(ar, discs_, out_dir_, name);
  serialize_series(ar, walls_, out_dir_, name + "_walls");
}

namespace {

void serialize_discs(StateArchive& ar, DemBody& b) {
  ar.section("discs");
  Discs& d = b.discs;
  const size_t n = d.size();
  ar.io(d.radius, d.mass, d.inertia, d.id, d.mark, d.group, b.where);
  ar.io(b.state.t, b.state.x, b.state.v, b.state.a, b.inv_mass, b.force);
  if (ar.loading()) {
    const size_t m = d.radius.size();
    for (size_t k : {d.mass.size(), d.inertia.size(), d.id.size(), d.mark.size(), d.group.size(), b.where.size()})
      if (k != m) throw CheckpointError("the discs' arrays differ in size");
    for (auto k : {b.state.x.size(), b.state.v.size(), b.state.a.size(), b.inv_mass.size(), b.force.size()})
      if (static_cast<size_t>(k) != 3 * m) throw CheckpointError("the discs' dofs differ in size");
    if (m != n) throw CheckpointError("another number of discs");
  }
}

void serialize_lists(StateArchive& ar, DemBody& b) {
  ar.section("pairs");
  PairList& P = b.pairs;
  ar.io(P.i, P.j, P.row, P.inc_row, P.inc);
  ar.io(b.history, b.pair_force, b.pair_rupture, b.pair_roll, b.x_build, b.wall_offset_build);
  ar.section("wall contacts");
  ar.io(b.wall_row, b.wall_seg, b.wall_history, b.wall_force);
  ar.io(b.rebuilds);
  if (ar.loading()) {
    const size_t np = P.i.size(), n = b.size();
    if (P.j.size() != np || b.history.size() != np || b.pair_force.size() != 3 * np || b.pair_rupture.size() != np ||
        P.row.size() != n + 1 || P.inc_row.size() != n + 1 || P.inc.size() != 2 * np || b.x_build.size() != 2 * n ||
        b.wall_row.size() != n + 1 || b.wall_history.size() != b.wall_seg.size() ||
        b.wall_force.size() != 2 * b.wall_seg.size() || b.wall_offset_build.size() != b.walls.size())
      throw CheckpointError("the neighbour lists differ in size");
  }
}

}  // namespace

void DemModel::serialize(StateArchive& ar) {
  DemBody& b = *body_;
  ar.section("dem " + b.name);
  serialize_discs(ar, b);
  serialize_lists(ar, b);
  ar.section("walls");
  std::uint64_t nw = b.walls.size();
  ar.io(nw);
  if (ar.loading() && nw != b.walls.size()) throw CheckpointError("another number of walls");
  for (Wall& w : b.walls) ar.io(w.offset);
  ar.section("blast");
  bool blast = b.blast.has_value();
  ar.io(blast);
  if (ar.loading() && blast != b.blast.has_value()) throw CheckpointError("a blast where the case has none, or none");
  if (b.blast) b.blast->serialize(ar);
  ar.io(b.blast_force);
  ar.section("energy");
  ar.io(b.elastic, b.dissipated, b.blast_work, b.energy0, b.crater.surface);
  ar.io(b.wall_work, b.energy_ref, b.energy_scale);
  ar.section("counters");
  ar.io(b.substeps, b.t_force, b.t_rebuild, b.t_blast, wall_time_);
  writer_->serialize(ar, b.name);
}

}  // namespace dem

}  // namespace lagfsi
