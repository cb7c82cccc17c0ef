#pragma once
/// @file mls.hpp
/// Moving least squares (MLS) approximation of the element-free Galerkin method (Belytschko, Lu & Gu 1994;
/// the INSANE EFG thesis, UFMG c. 2012, §2.2.3, digest shared/spec/003_efg.md §2.2, §2.5, Algorithm 5).
///
///   u^h(x) = sum_j N_j(x) v_j,   N_j(x) = p^T(x) M^{-1}(x) B_j(x),   B_j = phi_j(x) p(x_j)          (2.21-2.25)
///   M(x)   = sum_j phi_j(x) p(x_j) p^T(x_j)                                               (moment matrix, 2.16)
///
/// Derivatives by the gamma formulation (2.26-2.31): M gamma = p, M gamma_,k = p_,k - M_,k gamma,
/// N_j,k = gamma_,k^T B_j + gamma^T B_j,k.
///
/// Continuous FE-EFG coupling (Huerta & Fernandez-Mendez 2000; thesis 2.85-2.89): where active finite-element
/// nodes i in I^h act with FE shape functions N^h_i, the particle functions are corrected so that the sum
/// reproduces the basis:  M alpha = p(x) - S,  S = sum_i N^h_i(x) p(x_i);  M alpha_,k = p_,k - S_,k - M_,k alpha;
/// Ntilde_j = alpha^T p(x_j) phi_j,  Ntilde_j,k = alpha_,k^T p(x_j) phi_j + alpha^T p(x_j) phi_j,k.
/// (With S = 0 this is the plain MLS above, alpha = gamma.)
///
/// The basis is evaluated shifted and scaled, p((y - x)/s) with x the evaluation point held fixed and s the
/// mean domain size of the support ("MlsShape2DShifted" of the thesis): the functions are the same (the bases
/// are translation invariant) and M has entries of order one, so its conditioning measures the node layout.
#include <lagfsi/types.hpp>

#include <string>
#include <vector>

namespace lagfsi::efg {

/// Polynomial bases. The thesis's names: "hierarchical" = tensor product (i, j <= k), "serendipity"/"Poly"
/// = complete (i + j <= k).
enum class BasisType {
  linear,       ///< {1, x, y}: complete P1
  bilinear,     ///< {1, x, y, xy}: tensor product degree 1 ("hierarchical 1", "P1" in the thesis)
  quadratic,    ///< {1, x, y, xy, x^2, y^2}: complete P2 ("P2" in the thesis)
  biquadratic,  ///< {1, x, y, xy, x^2, x^2 y, y^2, x y^2, x^2 y^2}: tensor product degree 2
};

struct Basis {
  BasisType type = BasisType::bilinear;
  int size() const;
  /// Highest complete degree the basis reproduces (1 or 2).
  int complete_degree() const;
  /// p, dp/dx, dp/dy at (x, y); any output pointer may be null. Arrays of size() entries.
  void eval(double x, double y, double* p, double* px, double* py) const;
  static BasisType parse(const std::string& name);  ///< throws std::invalid_argument
  static const std::vector<std::string>& names();
};

/// Weight functions of the normalised distance r >= 0 (phi = 0 for r >= 1), thesis Eqs. 2.32-2.35.
enum class WeightType {
  cubic_spline,    ///< 2/3 - 4r^2 + 4r^3 (r <= 1/2); 4/3 - 4r + 4r^2 - 4/3 r^3 (1/2 < r <= 1)
  quartic_spline,  ///< 1 - 6r^2 + 8r^3 - 3r^4
  exponential,     ///< exp(-(r/a)^2), a = 0.3 (Liu 2003)
  quartic_alt,     ///< 2/3 - 9/2 r^2 + 19/3 r^3 - 5/2 r^4
};

struct Weight {
  WeightType type = WeightType::cubic_spline;
  double exp_alpha = 0.3;
  /// phi(r) and dphi/dr.
  void eval(double r, double& w, double& dw) const;
  static WeightType parse(const std::string& name);
  static const std::vector<std::string>& names();
};

/// Influence-domain geometry (thesis Eq. 2.36): rectangular (tensorial) phi(r_x) phi(r_y), r_x = |x - x_j|/rho_x,
/// or circular phi(|x - x_j| / rho).
enum class DomainShape { rectangular, circular };

struct InfluenceDomain {
  DomainShape shape = DomainShape::rectangular;
  Weight weight;
  /// True if x lies strictly inside the domain of a node at xj with sizes rho (circular: rho.x()).
  bool contains(const Vec2& x, const Vec2& xj, const Vec2& rho) const;
  /// Weight of the node at xj seen from x, and its gradient with respect to x.
  void eval(const Vec2& x, const Vec2& xj, const Vec2& rho, double& w, double& wx, double& wy) const;
};

/// Finite-element shape functions of active FE nodes at the evaluation point (the FE-EFG coupling); at most 9.
struct FeCorrection {
  int n = 0;
  Vec2 x[9];
  double N[9], Nx[9], Ny[9];
};

/// Shape functions at one point: support nodes and N, dN/dx, dN/dy.
struct ShapeValues {
  std::vector<Index> nodes;
  std::vector<double> N, Nx, Ny;
  double rcond = 1;  ///< reciprocal condition estimate of the moment matrix
};

class MlsShape {
 public:
  MlsShape() = default;
  MlsShape(Basis basis, InfluenceDomain domain, double rcond_min = 1e-12)
      : basis_(basis), domain_(domain), rcond_min_(rcond_min) {}
  const Basis& basis() const { return basis_; }
  const InfluenceDomain& domain() const { return domain_; }

  /// Shape functions at x from the candidate nodes `support` (already filtered for visibility; nodes whose
  /// domain does not contain x are dropped). Throws SolverError "MLS at (x, y) [where]: ..." when fewer nodes
  /// than basis terms remain or the moment matrix is ill-conditioned (reciprocal condition < rcond_min), naming
  /// the point, its support size and the condition estimate. With `fe`, the coupled (corrected) functions.
  /// A singular M whose right-hand sides (p, p_,k - M_,k gamma) lie in its range (checked) is solved by the
  /// pseudo-inverse: the functions are then still consistent. That happens at a node or on a cell edge when rho = h
  /// (only the nodes of the edge see the point; the functions are then the FE interpolation there) and with
  /// active FE nodes; a Gauss point of a proper layout never needs it. derivatives = false: only N is needed
  /// (nodal values, boundary loads), so only p must lie in the range (Nx, Ny are then meaningless).
  void compute(const Vec2& x, const std::vector<Vec2>& nodes, const std::vector<Vec2>& rho,
               const std::vector<Index>& support, ShapeValues& out, const FeCorrection* fe = nullptr,
               const std::string& where = "", bool derivatives = true) const;

 private:
  Basis basis_;
  InfluenceDomain domain_;
  double rcond_min_ = 1e-12;
};

}  // namespace lagfsi::efg
