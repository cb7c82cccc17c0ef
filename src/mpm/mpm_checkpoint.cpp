// Checkpoints of an MPM body (state_archive.hpp): the particles with their stresses and history variables,
// the body's clock and gravity work, the free-field columns' dynamic state, the grid's nodal arrays and the
// supports of the last sub-step (what the grid output and the probes show), and the output series. Taken
// after a step; a restart reads it over the state the body was built with.
#include "mpm_body.hpp"
#include "mpm_output.hpp"

#include <lagfsi/mpm/mpm_model.hpp>

namespace lagfsi::mpm {

namespace {

void serialize_particles(StateArchive& ar, Particles& P) {
  ar.section("particles");
  ar.io(P.x, P.X, P.v, P.mass, P.volume0, P.volume, P.F, P.stress, P.strain, P.plastic_multiplier);
  ar.io(P.strain_rate, P.porosity, P.pore_pressure, P.water_velocity, P.acceleration);
  const size_t n = P.x.size();
  for (size_t m : {P.X.size(), P.v.size(), P.mass.size(), P.volume0.size(), P.volume.size(), P.F.size(),
                   P.stress.size(), P.strain.size()})
    if (ar.loading() && m != n) throw CheckpointError("the particles' arrays differ in size");
}

}  // namespace

void MpmWriter::serialize(StateArchive& ar, const std::string& name) {
  serialize_series(ar, series_, out_dir_, name);
  serialize_series(ar, grid_series_, out_dir_, name + "_grid");
}

void MpmModel::serialize(StateArchive& ar) {
  MpmBody& b = *body_;
  ar.section("mpm " + b.name);
  serialize_particles(ar, b.particles);
  ar.io(b.t, b.gravity_work, substeps_);
  ar.section("grid");
  ar.io(b.grid.mass, b.grid.momentum, b.grid.force, b.grid.velocity);
  std::uint64_t ns = b.support.size();
  ar.io(ns);
  if (ar.loading()) b.support.resize(ns);
  for (Support& s : b.support) ar.io(s.n, s.node, s.N, s.dN);
  ar.section("free fields");
  std::uint64_t nf = b.boundaries.free_fields.size();
  ar.io(nf);
  if (ar.loading() && nf != b.boundaries.free_fields.size())
    throw CheckpointError("another number of free-field columns");
  for (FreeField& f : b.boundaries.free_fields) ar.io(f.u, f.v, f.reaction);
  writer_->serialize(ar, b.name);
}

}  // namespace lagfsi::mpm
