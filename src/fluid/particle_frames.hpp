#pragma once
/// @file particle_frames.hpp (private to src/fluid)
/// The frames of the particles that a boundary holds on an inclined line: such a particle's unknowns are rotated,
/// u = n u_n + t u_t with n the line's unit normal and t = (-n_y, n_x), and u_n is the component the boundary
/// prescribes (Zienkiewicz & Taylor's skew boundary conditions). Every other particle keeps the x-y frame.
#include <lagfsi/types.hpp>

#include <vector>

namespace lagfsi::fluid {

class ParticleFrames {
 public:
  /// Per particle: the unit normal n of its line, zero for a particle in the x-y frame; empty when no particle
  /// is rotated.
  const std::vector<Vec2>& normals() const { return n_; }
  std::vector<Vec2>& normals() { return n_; }
  bool empty() const { return n_.empty(); }
  bool rotated(Index i) const {
    return i < static_cast<Index>(n_.size()) && (n_[static_cast<size_t>(i)].array() != 0.0).any();
  }
  /// Particle i's frame as the columns of a rotation, [n t] (the identity in the x-y frame): its components
  /// u_l = Q^T u, and u = Q u_l.
  Mat2 frame(Index i) const {
    Mat2 q;
    q << direction(i, 0), direction(i, 1);
    return q;
  }
  /// The unit vector of component c (0, 1) of particle i in its frame: n, t on an inclined line, else x, y.
  Vec2 direction(Index i, int c) const {
    if (!rotated(i)) return c == 0 ? Vec2::UnitX() : Vec2::UnitY();
    const Vec2 n = n_[static_cast<size_t>(i)];
    return c == 0 ? n : Vec2(-n.y(), n.x());
  }
  /// Component c of particle i's vector in its frame: of a global vector u (2 per particle), and of a 2-vector.
  double component(const Vec& u, Index i, int c) const {
    return rotated(i) ? direction(i, c).dot(u.segment<2>(2 * i)) : u[2 * i + c];
  }
  double along(const Vec2& w, Index i, int c) const { return rotated(i) ? direction(i, c).dot(w) : w[c]; }
  /// Sets component c of particle i's vector in its frame to `value`, the other one unchanged.
  void set_component(Vec& u, Index i, int c, double value) const {
    if (!rotated(i)) {
      u[2 * i + c] = value;
      return;
    }
    const Vec2 d = direction(i, c);
    u.segment<2>(2 * i) += (value - d.dot(u.segment<2>(2 * i))) * d;
  }

 private:
  std::vector<Vec2> n_;
};

}  // namespace lagfsi::fluid
