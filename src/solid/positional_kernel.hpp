#pragma once
// The quadrature-point kernel shared by the positional continuum (solid_body.cpp) and shell
// (shell_body.cpp) elements: with G = dN/dX (npe x 2, derivatives of the element's scalar shape
// functions with respect to reference coordinates in some orthonormal frame), F = x_e^T G, the second
// Piola-Kirchhoff stress S and its tangent D = dS/dE (Voigt 11, 22, 12 with engineering shear) in that
// frame, adds
//   f_{a alpha} += F_{alpha I} S_{IJ} G_{aJ} dV,
//   K_{a alpha, b gamma} += [B_{a alpha} : D : B_{b gamma} + delta_{alpha gamma} G_{aI} S_{IJ} G_{bJ}] dV,
// with B_{a alpha} = sym(G_{aI} F_{alpha J}) (Coda & Paccola 2008; Avancini 2018, ch. 3).
#include <lagfsi/types.hpp>

namespace lagfsi::detail {

template <int NPE>
inline void add_positional_point(const Eigen::Matrix<double, NPE, 2>& G, const Mat2& F, const Mat2& S,
                                 const Eigen::Matrix3d& D, double dV, Eigen::Matrix<double, 2 * NPE, 1>* fe,
                                 Eigen::Matrix<double, 2 * NPE, 2 * NPE>* Ke) {
  if (fe) {
    const Eigen::Matrix<double, 2, NPE> FSGt = F * S * G.transpose();
    for (int a = 0; a < NPE; ++a) fe->template segment<2>(2 * a) += FSGt.col(a) * dV;
  }
  if (Ke) {
    Eigen::Matrix<double, 3, 2 * NPE> B;
    for (int a = 0; a < NPE; ++a)
      for (int al = 0; al < 2; ++al) {
        const int col = 2 * a + al;
        B(0, col) = G(a, 0) * F(al, 0);
        B(1, col) = G(a, 1) * F(al, 1);
        B(2, col) = G(a, 0) * F(al, 1) + G(a, 1) * F(al, 0);
      }
    Ke->noalias() += B.transpose() * (D * dV) * B;
    const Eigen::Matrix<double, NPE, NPE> Kg = G * (S * dV) * G.transpose();
    for (int b = 0; b < NPE; ++b)
      for (int a = 0; a < NPE; ++a) {
        (*Ke)(2 * a, 2 * b) += Kg(a, b);
        (*Ke)(2 * a + 1, 2 * b + 1) += Kg(a, b);
      }
  }
}

}  // namespace lagfsi::detail
