#pragma once
/// @file integration.hpp
/// Background-cell integration with optional integration consistency.
///
/// Gauss quadrature of rational MLS functions is not exact, so plain Gauss EFG passes the patch tests only to the
/// quadrature error (Dolbow & Belytschko 1999; the thesis §5.2 sees its effect on the nonlinear paths). The
/// "consistent" option corrects the shape-function derivatives at a cell's Gauss points by a polynomial per node,
/// N~_I,i = N_I,i + sum_r a_Iir r(x), r in Q, chosen so that the cell's discrete divergence identity holds for every
/// q in Q:
///   sum_g w_g N~_I,i q(x_g) = sum_e w_e N_I q n_i (x_e) - sum_g w_g N_I q_,i (x_g)
/// (e: Gauss points on the cell's edges). Q = {1} for a linear basis (the linear integration constraint of Chen et al.
/// 2001), Q = {1, x, y} for a quadratic one (the quadratic constraint of Duan, Li & Belytschko 2012). Interior edges
/// cancel between neighbouring cells and the boundary edges are those of the traction loads (same edge rule), so
/// linear (quadratic with the matching body force) patch tests are passed to round-off; the correction leaves the
/// consistency of the derivatives intact (it vanishes on the basis up to the rule's exactness).
#include <lagfsi/types.hpp>

#include <Eigen/Core>
#include <vector>

namespace lagfsi::efg {

/// Corrects Nx, Ny (Gauss points x nodes) of one cell in place. xg, wg: Gauss points and weights; N: values there;
/// xe, wn: edge points and (weight x outward normal); Ne: values at the edge points; degree 1 or 2.
void correct_derivatives(int degree, const std::vector<Vec2>& xg, const std::vector<double>& wg,
                         const Eigen::MatrixXd& N, const std::vector<Vec2>& xe, const std::vector<Vec2>& wn,
                         const Eigen::MatrixXd& Ne, Eigen::MatrixXd& Nx, Eigen::MatrixXd& Ny);

}  // namespace lagfsi::efg
