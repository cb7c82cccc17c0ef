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
///   K_{a alpha, b gamma} = int_{Omega0} [ B_{a alpha} : D : B_{b gamma} + delta_{alpha gamma} N_{a,I} S_{IJ} N_{b,J} ] dV,
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
#include <lagfsi/types.hpp>

#include <memory>
#include <vector>

namespace lagfsi {

class SolidBody {
 public:
  SolidBody(TriMesh reference, std::shared_ptr<const SolidMaterial> material, double thickness);

  const TriMesh& mesh() const { return mesh_; }
  const SolidMaterial& material() const { return *material_; }
  double thickness() const { return thickness_; }
  Index num_nodes() const { return mesh_.num_nodes(); }
  Index num_dofs() const { return 2 * mesh_.num_nodes(); }
  /// Reference positions as a dof vector [X0, Y0, X1, Y1, ...].
  const Vec& reference_positions() const { return X_; }

  /// Empty matrix with the sparsity pattern of the body (full, both triangles).
  const SparseMatrix& pattern() const { return pattern_; }
  /// Consistent mass (same pattern).
  const SparseMatrix& mass() const { return mass_; }
  /// Lumped (row-sum) mass as a dof vector.
  Vec lumped_mass() const;

  /// Internal force f_int(x) and, if K is not null, the tangent K = d f_int / dx written into K's values
  /// (K must have pattern()'s structure; values are overwritten). Returns the strain energy.
  /// Throws SolverError on an inverted element (det F <= 0) or a non-finite value.
  double internal_force(const Vec& x, Vec& f, SparseMatrix* K) const;

  /// Strain energy only.
  double strain_energy(const Vec& x) const;

  /// Nodal fields at x (averaged over the elements around each node, evaluated at the nodes):
  /// Cauchy stress (xx, yy, xy, zz), von Mises, Green strain (xx, yy, xy).
  struct NodalStress {
    std::vector<double> cauchy;      // 4 per node
    std::vector<double> von_mises;   // 1 per node
    std::vector<double> green;       // 3 per node
  };
  NodalStress nodal_stress(const Vec& x) const;

  /// Consistent nodal forces of a uniform body force b (per unit reference volume): M g with g = b / rho.
  Vec body_force(const Vec2& force_per_volume) const;
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
  std::shared_ptr<const SolidMaterial> material_;
  double thickness_;
  Vec X_;
  SparseMatrix pattern_, mass_;
  ElementPattern assembly_;                  // pattern, scatter map and element colours
  std::vector<Eigen::MatrixX2d> qdN_;        // parent derivatives at the quadrature points
  std::vector<double> qw_;                   // quadrature weights
};

}  // namespace lagfsi
