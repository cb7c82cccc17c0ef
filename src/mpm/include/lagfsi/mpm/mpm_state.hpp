#pragma once
/// @file mpm/mpm_state.hpp
/// State of an MPM body: its particles (structure of arrays), the regular background grid with the nodal
/// arrays of the transfers, and the shape functions that tie them (a particle's support: the nodes within
/// reach with N_Ip and grad N_Ip).
///
/// Shape functions: "linear" (tent functions of the cells) or "gimp" (uGIMP: particle domains of half-width
/// lp = h / (2 n), n particles per cell per direction, which removes most of the cell-crossing noise;
/// Bardenhagen & Kober 2004). Plane strain, unit thickness.
#include <lagfsi/types.hpp>

#include <array>
#include <cstddef>
#include <vector>

namespace lagfsi::mpm {

/// Stress (xx, yy, xy, zz), tension positive.
using Stress = std::array<double, 4>;

/// Particles of one body (structure of arrays).
struct Particles {
  std::vector<Vec2> x, X, v;                  ///< current position, reference position, velocity
  std::vector<double> mass, volume0, volume;  ///< mass, initial and current volume
  std::vector<Mat2> F;                        ///< deformation gradient
  std::vector<Stress> stress;
  std::vector<std::array<double, 3>> strain;       ///< small strain xx, yy, xy (engineering/2: tensor xy)
  std::vector<double> plastic_multiplier;          ///< accumulated plastic multiplier (equivalent plastic shear)
  std::vector<std::array<double, 3>> strain_rate;  ///< last strain rate xx, yy, xy
  // Two-phase (saturated) bodies: porosity, water velocity, pore pressure (tension positive, as in the
  // formulation; output as compression-positive "pore_pressure").
  std::vector<double> porosity, pore_pressure;
  std::vector<Vec2> water_velocity;
  std::vector<Vec2> acceleration;  ///< last acceleration (grid to particle)

  size_t size() const { return x.size(); }
  /// Appends a particle at rest at x (reference position x), unstrained and unstressed.
  void add(const Vec2& position, double particle_mass, double particle_volume);
};

/// The regular background grid: (nx + 1) x (ny + 1) nodes, node (i, j) at origin + h (i, j), numbered
/// j (nx + 1) + i; and the nodal arrays of the single-phase transfers (of the last sub-step).
struct Grid {
  Vec2 origin = Vec2::Zero();
  double h = 1;        ///< cell size
  int nx = 0, ny = 0;  ///< cells per direction

  std::vector<double> mass;    ///< m_I = sum_p N_Ip m_p
  std::vector<Vec2> momentum;  ///< (m v)_I = sum_p N_Ip m_p v_p, then advanced by dt f_I
  std::vector<Vec2> force;     ///< f_I: internal, gravity, loads, damping and boundary forces
  std::vector<Vec2> velocity;  ///< v_I = (m v)_I / m_I

  size_t num_nodes() const { return static_cast<size_t>(nx + 1) * static_cast<size_t>(ny + 1); }
  Vec2 node_position(int i, int j) const { return origin + Vec2(i * h, j * h); }
  /// Positions of all nodes in their numbering.
  std::vector<Vec2> node_positions() const;
  /// Whether x lies in the grid (boundary included).
  bool contains(const Vec2& x) const {
    return x.x() >= origin.x() && x.y() >= origin.y() && x.x() <= origin.x() + nx * h && x.y() <= origin.y() + ny * h;
  }
  /// Sizes the nodal arrays to the grid's nodes, zeroed.
  void allocate();
};

/// Up to 3 x 3 nodes of one particle with their shape function values and gradients.
struct Support {
  int n = 0;
  std::array<Index, 9> node;
  std::array<double, 9> N;
  std::array<Vec2, 9> dN;
};

/// The shape functions of the grid: linear or uGIMP with particle domains of half-width h / (2 n).
struct ShapeFunctions {
  bool gimp = false;
  int particles_per_cell = 2;  ///< n per direction (the GIMP particle domain)
  /// Support of a particle at x (inside the grid): the nodes whose function or gradient is non-zero there.
  void evaluate(const Grid& grid, const Vec2& x, Support& s) const;
};

/// Supports of every particle at its current position (in parallel for large bodies). Returns the index of a
/// particle that has left the grid (its support is not computed), or -1 when all are inside.
Index locate_particles(const Grid& grid, const ShapeFunctions& shape, const Particles& particles,
                       std::vector<Support>& support);

}  // namespace lagfsi::mpm
