#pragma once
/// @file dem/dem_neighbour_grid.hpp
/// Neighbour search of the DEM body on a uniform cell grid (the "screening" of Munjiza 2004, ch. 2): the
/// discs are binned into square cells of side >= 2 r_max + skin, and each disc is tested against the discs of
/// its own cell and of the four "forward" cells (E, NW, N, NE), so each pair is found once (a half list).
/// A pair is listed when |c_i - c_j| < r_i + r_j + skin (a Verlet list with skin); the list stays valid until
/// a disc has moved more than skin/2 since the build (the model's rebuild criterion).
///
/// The list is stored by owner (CSR: the pairs of owner p are row[p] .. row[p+1]) and, for the race-free
/// force sweep, with its incidence (the pairs each disc takes part in, in pair order): pair forces are
/// computed in parallel into a per-pair buffer, then each disc sums its pairs in a fixed order, so the result
/// does not depend on the number of threads.
///
/// Positions are read with a stride (3 for the (x, y, theta) dofs of the model).
#include <lagfsi/types.hpp>

#include <vector>

namespace lagfsi::dem {

struct PairList {
  std::vector<Index> i, j;     ///< pair k = (i[k], j[k]), owner i
  std::vector<Index> row;      ///< size n + 1: pairs of owner p are row[p] .. row[p + 1]
  std::vector<Index> inc_row;  ///< size n + 1: incidences of disc p are inc[inc_row[p] .. inc_row[p + 1]]
  std::vector<Index> inc;      ///< 2 k (disc is i of pair k) or 2 k + 1 (disc is j)
  size_t size() const { return i.size(); }
  /// Index of the pair (a, b) or (b, a), or -1.
  Index find(Index a, Index b) const;
};

class NeighbourGrid {
 public:
  /// Bins n discs (positions x[stride k], x[stride k + 1]) into cells of side >= `cell` over their bounding
  /// box (the side grows if the box would need more than 4 n + 1024 cells, e.g. with far-flung ejecta).
  void bin(const double* x, int stride, Index n, double cell);
  /// The discs in cell order (a permutation new -> old that makes neighbours close in memory).
  const std::vector<Index>& order() const { return order_; }
  /// Half list of the pairs with |c_i - c_j| < r_i + r_j + skin (after bin() with the same positions).
  void build(const double* x, int stride, const double* r, Index n, double skin, PairList& out) const;
  double cell_size() const { return h_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }

 private:
  int cell_of(double x, double y) const;
  double x0_ = 0, y0_ = 0, h_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<Index> cell_;        ///< cell of each disc
  std::vector<Index> cell_start_;  ///< discs of cell c: order_[cell_start_[c] .. cell_start_[c + 1]]
  std::vector<Index> order_;
  std::vector<Index> pos_;  ///< position of disc p in order_
};

/// All pairs with |c_i - c_j| < r_i + r_j + skin by testing every pair (for tests), as (min, max) sorted.
std::vector<std::pair<Index, Index>> brute_force_pairs(const double* x, int stride, const double* r, Index n,
                                                       double skin);

}  // namespace lagfsi::dem
