#pragma once
/// @file ghosts.hpp (private to src/fluid)
/// The ghost particles of the fluid's InterfaceFluid side (interface.hpp): particles that follow a
/// structure's wet boundary, join the remeshing, and take the forces the fluid exerts on the structure.
#include <lagfsi/fluid/particle_cloud.hpp>
#include "fluid_common.hpp"
#include "fluid_mesh.hpp"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace lagfsi::fluid {

/// Ghost particles ghost_begin .. + ghost_particles in the cloud (after the walls, before the fluid, so their
/// indices never change); index(g) is ghost g's particle (a wall particle when merged); the step's
/// prescribed motion and the forces on them.
class Ghosts {
 public:
  /// InterfaceFluid::add_ghosts: ghosts on a wall particle (within h/4) are merged with it, the others become
  /// particles after the walls; the fluid particles within h/2 of one are dropped (the cloud is rebuilt:
  /// walls, ghosts, fluid). Returns the number of merged ghosts; `body` names the errors.
  int add(const std::vector<Vec2>& points, const std::vector<std::pair<Index, Index>>& adjacent, ParticleCloud& cloud,
          double h, const std::string& body);
  /// Ghost particles in the cloud (not merged with a wall particle).
  Index particles() const { return ghost_particles_; }
  /// Particle i is a ghost particle.
  bool is_ghost(Index i) const { return i >= ghost_begin_ && i < ghost_begin_ + ghost_particles_; }
  /// An element with two ghost particles that are not neighbours along the structure crosses it.
  bool crosses_structure(const std::array<Index, 3>& t) const;
  /// Ghost particle i's neighbours along the structure's face (ghost particles, or the wall particle a ghost
  /// was merged with); none for any other particle. Each pair is a segment of the wet face.
  const std::vector<Index>& face_neighbours(Index i) const;
  /// Element t has two or three particles with prescribed motion, one of them a ghost: a structure's boundary
  /// sliding past a wall or another part of it (a gate's tip over the floor). Such an element may turn over
  /// within a step without the flow being wrong; an element between walls alone that turns over is a failed
  /// step, as before (retried with dt/2).
  bool moving_boundary_pair(const std::array<Index, 3>& t, const std::vector<ParticleKind>& kind) const {
    int prescribed = 0;
    bool ghost = false;
    for (Index i : t) {
      prescribed += kind[i] != ParticleKind::Fluid;
      ghost = ghost || is_ghost(i);
    }
    return prescribed >= 2 && ghost;
  }

  /// InterfaceFluid::set_ghost_motion: the ghosts' motion at t_{n+1} (2 per ghost each).
  void set_motion(const Vec& x, const Vec& v, const Vec& a, const std::string& body);
  /// The ghosts' prescribed positions of the step into the iterate x (once a motion was given).
  void place(Vec& x) const;
  /// Ghost velocities and accelerations into v and a (the prescribed motion of the step).
  void set_rates(Vec& v, Vec& a) const;
  /// Whether an element of `mesh` uses a ghost particle (InterfaceFluid::in_contact, after predict).
  void update_contact(const FluidMesh& mesh);
  bool in_contact() const { return contact_; }

  /// Read access for the schemes: the ghosts (merged ones included), their particles, the given positions.
  size_t count() const { return ghost_index_.size(); }
  Index index(size_t g) const { return ghost_index_[g]; }
  bool merged(size_t g) const { return ghost_merged_[g] != 0; }
  const Vec& x() const { return ghost_x_; }
  /// Forces the fluid exerts on the ghosts (2 per ghost), set by the scheme's solve.
  Vec& forces() { return ghost_force_; }
  const Vec& forces() const { return ghost_force_; }
  /// Checkpoints (state_archive.hpp; fluid_checkpoint.cpp).
  void serialize(StateArchive& ar);

 private:
  Index ghost_begin_ = 0, ghost_particles_ = 0;
  std::vector<Index> ghost_index_;
  std::vector<char> ghost_merged_;
  std::vector<std::vector<Index>> ghost_neighbours_;  // per ghost particle (local), its face neighbours' particles
  Vec ghost_x_, ghost_v_, ghost_a_, ghost_force_;
  bool contact_ = false;
};

}  // namespace lagfsi::fluid
