#pragma once
/// @file solid.hpp
/// Positional finite elements for 2D solids (Coda 2003; Coda & Paccola 2008; Avancini 2018, ch. 3 and 5).
///
/// The unknowns are the current nodal positions x (2 per node, dof 2 i + c). With the parent map of the
/// initial configuration A0 = dX/dxi and of the current one A1 = dx/dxi, the deformation gradient is
/// F = A1 A0^-1; the Green strain is E = (F^T F - I)/2 and a hyperelastic law gives S(E). The internal
/// force and its exact Hessian are
///
///   f_{a alpha} = int_{Omega0} F_{alpha I} S_{IJ} N_{a,J} dV,
///   K_{a alpha, b gamma} = int_{Omega0} [ B_{a alpha} : D : B_{b gamma} + delta_{alpha gamma} N_{a,I} S_{IJ} N_{b,J} ]
///   dV,
///
/// with B_{a alpha} = dE/dx_{a alpha} = sym(N_{a,I} F_{alpha J}); dV carries the thickness (plane stress) or a
/// unit thickness (plane strain, unless one is given). The consistent mass M_ab = int rho0 N_a N_b dV I is
/// constant (total Lagrangian). Quadrature: the Dunavant rule of degree 2p (T3: 3 points, T6: 6, T10: 12),
/// which integrates the mass exactly and the small-strain stiffness exactly on straight-sided elements.
///
/// Assembly writes into a fixed CSC pattern through a per-element scatter map, in parallel (OpenMP) over
/// element colours (no two elements of a colour share a node), so no atomics are needed.
#include <lagfsi/assembly.hpp>
#include <lagfsi/material.hpp>
#include <lagfsi/mesh.hpp>
#include <lagfsi/time_integrator.hpp>
#include <lagfsi/types.hpp>

#include <memory>
#include <utility>
#include <vector>

namespace lagfsi {

class PvdSeries;

/// A point of a structure's surface as a linear combination of at most two dof nodes:
/// x = x[node] + c x[other] (other < 0: x = x[node]). A continuum's surface points are its nodes; a shell's
/// are x_m + eta g (mid-line node plus eta times the generalised vector).
struct SurfacePoint {
  Index node = 0;
  Index other = -1;
  double c = 0.0;
};

/// What the solid model (Newton, integrators, loads, boundary conditions, probes, coupling) needs from a
/// positional structural discretisation: unknowns are 2D vectors ("dof nodes", 2 dofs each, dof 2 i + c)
/// whose mass matrix is constant (total Lagrangian). Implemented by SolidBody (continuum triangles) and
/// ShellBody (shell.hpp: positional frame/shell elements).
class StructuralBody {
 public:
  virtual ~StructuralBody() = default;
  virtual Index num_nodes() const = 0;
  Index num_dofs() const { return 2 * num_nodes(); }
  virtual Index num_elements() const = 0;
  /// Reference values of the unknowns as a dof vector.
  virtual const Vec& reference_positions() const = 0;
  /// Empty matrix with the sparsity pattern of the body (full, both triangles).
  virtual const SparseMatrix& pattern() const = 0;
  /// Consistent mass (same pattern).
  virtual const SparseMatrix& mass() const = 0;
  /// Internal force f_int(x) and, if K is not null, the tangent K = d f_int / dx written into K's values
  /// (K must have pattern()'s structure; values are overwritten). Returns the strain energy.
  /// Throws SolverError on an inverted element (det F <= 0) or a non-finite value.
  virtual double internal_force(const Vec& x, Vec& f, SparseMatrix* K) const = 0;
  /// Consistent nodal forces of a uniform body force b (per unit reference volume).
  virtual Vec body_force(const Vec2& force_per_volume) const = 0;
  virtual double density() const = 0;
  /// Out-of-plane thickness (plane stress) or width that multiplies areas into volumes.
  virtual double out_of_plane() const = 0;

  /// Stations: the reference points where boundary conditions and point loads act (a continuum's nodes,
  /// a shell's mid-line nodes). station_node(s) is the dof node that carries the station's translation;
  /// station_rotation_node(s) the one that carries its rotation (a shell's generalised vector; -1 if none).
  virtual const std::vector<Vec2>& stations() const = 0;
  virtual Index station_node(Index s) const { return s; }
  virtual Index station_rotation_node(Index) const { return -1; }

  /// The boundary: surface points and edges (order+1 surface point ids each, from the first vertex to the
  /// second, traversing the boundary counter-clockwise, so the outward normal is on the right).
  virtual const std::vector<SurfacePoint>& surface_points() const = 0;
  virtual const std::vector<std::vector<Index>>& surface_edges() const = 0;
  virtual int surface_order() const = 0;
  /// Surface point positions for a dof vector (2 per point of `points`).
  Vec surface_values(const std::vector<Index>& points, const Vec& full) const;
  /// Adds point forces (2 per point of `points`) to a dof vector: the transpose of surface_values.
  void add_surface_forces(const std::vector<Index>& points, const Vec& forces, Vec& full) const;

  /// Weights w_k of dof nodes such that the position (or displacement) at reference point P is
  /// sum_k w_k x[node_k]; false if P is not in the body.
  virtual bool locate(const Vec2& P, std::vector<std::pair<Index, double>>& weights) const = 0;

  /// Writes the state into the body's ParaView series (a .vtu or .vtp per call).
  virtual void write_output(PvdSeries& series, double t, const KinematicState& s) const = 0;
};

/// Consistent nodal forces of a dead traction t (force per unit reference length of the boundary, times
/// out_of_plane()) on surface edges of `body`.
Vec surface_traction(const StructuralBody& body, const std::vector<std::vector<Index>>& edges, const Vec2& t);

/// The matrix P of a unit follower pressure on surface edges: the nodal forces of pressure p pushing on the
/// current boundary are f(x) = p P x (in 2D the current normal times the length element is linear in x:
/// n ds = (dy, -dx) for a counter-clockwise boundary), so the load's tangent is -p P. P has the body's
/// pattern (an edge's points belong to one element).
SparseMatrix follower_pressure_matrix(const StructuralBody& body, const std::vector<std::vector<Index>>& edges);

class SolidBody final : public StructuralBody {
 public:
  SolidBody(TriMesh reference, std::shared_ptr<const SolidMaterial> material, double thickness);

  const TriMesh& mesh() const { return mesh_; }
  const SolidMaterial& material() const { return *material_; }
  double thickness() const { return thickness_; }
  Index num_nodes() const override { return mesh_.num_nodes(); }
  Index num_elements() const override { return mesh_.num_elements(); }
  /// Reference positions as a dof vector [X0, Y0, X1, Y1, ...].
  const Vec& reference_positions() const override { return X_; }

  const SparseMatrix& pattern() const override { return pattern_; }
  const SparseMatrix& mass() const override { return mass_; }
  /// Lumped (row-sum) mass as a dof vector.
  Vec lumped_mass() const;

  double internal_force(const Vec& x, Vec& f, SparseMatrix* K) const override;
  double density() const override { return material_->density(); }
  double out_of_plane() const override { return thickness_; }

  /// Strain energy only.
  double strain_energy(const Vec& x) const;

  const std::vector<Vec2>& stations() const override { return mesh_.nodes; }
  const std::vector<SurfacePoint>& surface_points() const override { return surface_points_; }
  const std::vector<std::vector<Index>>& surface_edges() const override { return surface_edges_; }
  int surface_order() const override { return mesh_.order; }
  bool locate(const Vec2& P, std::vector<std::pair<Index, double>>& weights) const override;
  void write_output(PvdSeries& series, double t, const KinematicState& s) const override;

  /// Nodal fields at x (averaged over the elements around each node, evaluated at the nodes):
  /// Cauchy stress (xx, yy, xy, zz), von Mises, Green strain (xx, yy, xy).
  struct NodalStress {
    std::vector<double> cauchy;     // 4 per node
    std::vector<double> von_mises;  // 1 per node
    std::vector<double> green;      // 3 per node
  };
  NodalStress nodal_stress(const Vec& x) const;

  /// Consistent nodal forces of a uniform body force b (per unit reference volume): M g with g = b / rho.
  Vec body_force(const Vec2& force_per_volume) const override;
  /// Consistent nodal forces of a traction t (force per unit reference area) on boundary edges given
  /// as order+1 node lists from the mesh's boundary_edges().
  Vec edge_traction(const std::vector<std::vector<Index>>& edges, const Vec2& t) const;

  /// Element containing reference point P and its parent coordinates (straight-sided elements);
  /// returns false if P is outside every element (beyond a relative tolerance).
  bool locate(const Vec2& P, Index& element, double& xi1, double& xi2) const;

  int quadrature_degree() const { return 2 * mesh_.order; }

 private:
  template <int NPE>
  double assemble(const Vec& x, Vec& f, SparseMatrix* K, bool need_force) const;
  void build_pattern();
  void build_mass();

  TriMesh mesh_;
  std::vector<SurfacePoint> surface_points_;
  std::vector<std::vector<Index>> surface_edges_;
  std::shared_ptr<const SolidMaterial> material_;
  double thickness_;
  Vec X_;
  SparseMatrix pattern_, mass_;
  ElementPattern assembly_;            // pattern, scatter map and element colours
  std::vector<Eigen::MatrixX2d> qdN_;  // parent derivatives at the quadrature points
  std::vector<double> qw_;             // quadrature weights
};

}  // namespace lagfsi
