#pragma once
/// @file shell.hpp
/// Positional frame/shell elements for thin walls in 2D (Coda & Greco 2004, Comput. Methods Appl. Mech.
/// Engrg. 193:3541; Coda 2009, "generalised vector" frames; Reissner kinematics).
///
/// Unknowns per mid-line node a: its current position x_a and a generalised vector g_a (unconstrained: it
/// rotates, stretches and need not stay normal to the mid-line, so shear and thickness change are
/// represented). Along an element of order p (1-3, Lagrange functions N_a(xi), xi in [0, 1]) the current
/// and reference maps of a point at thickness coordinate eta in [-1/2, 1/2] are
///
///   x(xi, eta) = sum_a N_a(xi) (x_a + eta g_a),     X(xi, eta) = sum_a N_a(xi) (X_a + eta G_a),
///
/// with G_a = t n_a (reference thickness t times the unit normal, on the left of the mid-line direction).
/// Both are linear in the unknowns, so the element is a positional continuum element whose 2(p+1) scalar
/// shape functions are {N_a, eta N_a}: F = A1 A0^-1 with A = d(x or X)/d(xi, eta), and the Green strain is
/// taken in the orthonormal frame (e1 along the reference mid-line, e2 normal to it), E = (F^T F - I)/2.
/// The "SVK-type law in the shell's own strain measures" is uncoupled in that frame,
///
///   S11 = Eb E11,   S22 = E E22,   S12 = kappa G (2 E12),
///
/// with Eb = E/(1 - nu^2) for a plate strip in plane strain or E for a beam (plane stress), kappa the shear
/// correction (default 5/6). Uncoupling E22 from E11 removes the Poisson thickness locking of linear
/// through-thickness kinematics (the transverse stress of a bent shell is ~0, which the uncoupled law gives
/// with a free thickness stretch). The shear term is integrated with p points along the element
/// (selective reduced integration against shear locking; "full" uses p + 1 like the others), three Gauss
/// points through the thickness (exact for the quadratic-in-eta strain energy of a straight element).
/// The mass matrix int rho Phi_A Phi_B dV is constant and includes the rotary inertia of the section.
/// Internal force and exact Hessian follow positional_kernel.hpp.
///
/// Dof nodes: 0..n-1 the mid-line nodes, n..2n-1 the generalised vectors (2 dofs each, dof 2 i + c).
/// Surface points: the two faces (eta = +1/2 "top", on the normal's side: ids 0..n-1; eta = -1/2
/// "bottom": ids n..2n-1) and the interior points of the two end edges (p - 1 each), so fluid ghost
/// particles, tractions and follower pressure act on the faces exactly like on a continuum boundary.
#include <lagfsi/solid/solid.hpp>

#include <vector>

namespace lagfsi {

struct ShellSection {
  double thickness = 0.0;    ///< reference thickness t (m)
  double width = 1.0;        ///< out-of-plane width b (m)
  double young = 0.0;        ///< E
  double poisson = 0.0;      ///< nu
  double density = 0.0;      ///< rho
  bool plane_strain = true;  ///< Eb = E/(1 - nu^2) (plate strip) instead of E (beam)
  double shear_correction = 5.0 / 6.0;
  bool reduced_shear = true;  ///< shear integrated with p points along the element
};

class ShellBody final : public StructuralBody {
 public:
  /// `midline`: the reference mid-line nodes in order, n = order * elements + 1 (element e uses nodes
  /// e*order .. e*order + order). Throws std::invalid_argument for bad input (order, counts, coincident
  /// nodes, non-positive section values).
  ShellBody(int order, std::vector<Vec2> midline, const ShellSection& section);

  int order() const { return order_; }
  const ShellSection& section() const { return sec_; }
  Index num_sections() const { return static_cast<Index>(mid_.size()); }
  Index num_nodes() const override { return 2 * num_sections(); }
  Index num_elements() const override { return (num_sections() - 1) / order_; }
  const Vec& reference_positions() const override { return X_; }
  const SparseMatrix& pattern() const override { return assembly_.pattern(); }
  const SparseMatrix& mass() const override { return mass_; }
  double internal_force(const Vec& x, Vec& f, SparseMatrix* K) const override;
  Vec body_force(const Vec2& force_per_volume) const override;
  double density() const override { return sec_.density; }
  double out_of_plane() const override { return sec_.width; }

  const std::vector<Vec2>& stations() const override { return mid_; }
  Index station_rotation_node(Index s) const override { return num_sections() + s; }
  const std::vector<SurfacePoint>& surface_points() const override { return surface_points_; }
  const std::vector<std::vector<Index>>& surface_edges() const override { return surface_edges_; }
  int surface_order() const override { return order_; }
  bool locate(const Vec2& P, std::vector<std::pair<Index, double>>& weights) const override;
  void write_output(PvdSeries& series, double t, const KinematicState& s) const override;

  /// Stress resultants per mid-line node (averaged over the elements at the node), from the second
  /// Piola-Kirchhoff stress in the reference frame of the section: axial force N = b t int S11 deta,
  /// shear force Q = b t int S12 deta, bending moment M = b t^2 int S11 eta deta (positive when it
  /// stretches the top face, eta > 0).
  struct Resultants {
    std::vector<double> axial, shear, moment;
  };
  Resultants resultants(const Vec& x) const;

 private:
  template <int NPE>
  double assemble(const Vec& x, Vec* f, SparseMatrix* K) const;
  void build_points();

  struct QuadPoint {
    Eigen::MatrixX2d G;   ///< d Phi / dX in the section's reference frame (npe x 2)
    Eigen::VectorXd Phi;  ///< the shape functions {N_a, eta N_a} (mass)
    double dV;
    bool shear_only;  ///< a point of the reduced shear rule
  };

  int order_;
  ShellSection sec_;
  double Eb_, Gs_;
  Eigen::Matrix3d Dfull_, Dshear_;
  std::vector<std::vector<QuadPoint>> points_;  ///< per element
  std::vector<Vec2> mid_;
  std::vector<Vec2> normal_;  ///< unit reference normals at the mid-line nodes
  Vec X_;
  ElementPattern assembly_;
  SparseMatrix mass_;
  std::vector<SurfacePoint> surface_points_;
  std::vector<std::vector<Index>> surface_edges_;
};

}  // namespace lagfsi
