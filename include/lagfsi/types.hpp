#pragma once
/// @file types.hpp
/// Basic numeric types shared by every lagfsi module.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

namespace lagfsi {

using Index = std::int32_t;  ///< node / element / dof index (sparse matrices use int)
using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using Vec = Eigen::VectorXd;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<double, int>;

}  // namespace lagfsi
