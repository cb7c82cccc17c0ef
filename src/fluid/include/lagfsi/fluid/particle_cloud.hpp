#pragma once
/// @file fluid/particle_cloud.hpp
/// The fluid's particles: the per-particle parallel arrays (kind, spacing, x, v, a, initial position,
/// pressure, owed area), kept aligned by the only operations that add, remove or reorder particles (compact,
/// append, rebuild). Implemented in src/fluid/particle_cloud.cpp.
#include <lagfsi/fluid/fluid_params.hpp>

#include <lagfsi/state_archive.hpp>
#include <lagfsi/time_integrator.hpp>

#include <algorithm>
#include <vector>

namespace lagfsi::fluid {

class ParticleCloud {
 public:
  /// One particle's data (for append and rebuild).
  struct Particle {
    ParticleKind kind = ParticleKind::Fluid;
    double h = 0;
    Vec2 x = Vec2::Zero(), v = Vec2::Zero(), a = Vec2::Zero(), X0 = Vec2::Zero();
    double p = 0;
    double owed = 0;
  };

  /// The initial cloud: particles at `x` of kinds `kind`, spacing h, at rest, zero pressure, X0 = x.
  void assign(const std::vector<Vec2>& x, std::vector<ParticleKind> kind, double h);

  Index n() const { return static_cast<Index>(kind_.size()); }
  const std::vector<ParticleKind>& kind() const { return kind_; }
  ParticleKind kind(Index i) const { return kind_[i]; }
  bool is_fluid(Index i) const { return kind_[i] == ParticleKind::Fluid; }
  /// Walls, then ghosts, come first in the cloud: the number of those leading non-fluid particles.
  Index n_boundary_particles() const {
    Index nb = 0;
    while (nb < n() && kind_[nb] != ParticleKind::Fluid) ++nb;
    return nb;
  }
  /// Per-particle spacing (the alpha test's and the filters' local h).
  const std::vector<double>& h() const { return hvec_; }
  double h(Index i) const { return hvec_[i]; }
  /// The largest particle size (0 without particles).
  double h_max() const { return hvec_.empty() ? 0.0 : *std::max_element(hvec_.begin(), hvec_.end()); }
  /// The smallest particle size (0 without particles).
  double h_min() const { return hvec_.empty() ? 0.0 : *std::min_element(hvec_.begin(), hvec_.end()); }
  /// A particle's size (an adaptive size field's target, size_field.hpp).
  void set_h(Index i, double h) { hvec_[static_cast<size_t>(i)] = h; }

  /// x, v, a of all particles (2 per particle; t is not used). The arrays' sizes are the cloud's: change
  /// them only through compact, append and rebuild.
  KinematicState& state() { return state_; }
  const KinematicState& state() const { return state_; }
  Vec& x() { return state_.x; }
  const Vec& x() const { return state_.x; }
  Vec& v() { return state_.v; }
  const Vec& v() const { return state_.v; }
  Vec& a() { return state_.a; }
  const Vec& a() const { return state_.a; }
  /// Initial positions (walls move relative to these).
  const Vec& X0() const { return X0_; }
  /// Pressures (one per particle, positive in compression).
  Vec& p() { return p_; }
  const Vec& p() const { return p_; }
  /// The area each particle is owed ("volume_correction": "particle", volume_correction.hpp): what the steps
  /// and the remeshing took from (positive) or gave to (negative) the particle's share of the mesh, not yet
  /// returned by the continuity equation. Zero at the start; a merged particle owes the pair's sum.
  Vec& owed() { return owed_; }
  const Vec& owed() const { return owed_; }

  Vec2 pos(Index i) const { return state_.x.segment<2>(2 * i); }
  Vec2 vel(Index i) const { return state_.v.segment<2>(2 * i); }
  /// The positions as points (for meshing).
  std::vector<Vec2> positions() const;
  Particle particle(Index i) const;

  /// Removes the flagged particles (drop[i] != 0), keeping the order of the others; false when none is
  /// flagged.
  bool compact(const std::vector<char>& drop);
  /// Adds particles at the end.
  void append(const std::vector<Particle>& added);
  /// The cloud rebuilt in a new order: entry k >= 0 of `order` is the present particle k, entry -1 - j is
  /// extra[j].
  void rebuild(const std::vector<Index>& order, const std::vector<Particle>& extra);
  /// Checkpoints (state_archive.hpp; fluid_checkpoint.cpp).
  void serialize(StateArchive& ar);

 private:
  std::vector<ParticleKind> kind_;
  std::vector<double> hvec_;
  KinematicState state_;  // x, v, a of all particles
  Vec X0_;
  Vec p_;
  Vec owed_;
};

}  // namespace lagfsi::fluid
