#pragma once
/// @file assembly.hpp
/// Sparse assembly on a fixed pattern: the CSC pattern of a mesh with `dofs_per_node` unknowns per node
/// (dof = dofs_per_node * node + component), and for each element the positions in the value array of its
/// (npe*dofs_per_node)^2 local entries (the "scatter map"), so that assembling a local matrix is a sequence
/// of indexed additions. Elements are coloured (no two elements of a colour share a node) so that OpenMP
/// threads can add whole elements without atomics.
#include <lagfsi/types.hpp>

#include <vector>

namespace lagfsi {

class ElementPattern {
 public:
  ElementPattern() = default;
  /// conn: npe node indices per element; num_nodes: nodes of the mesh (nodes in no element get a
  /// diagonal entry so that the matrix stays square and can carry a Dirichlet 1 on them).
  ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dofs_per_node);
  /// Only the elements e with keep[e] != 0 (keep has one entry per element of conn): the pattern has their
  /// entries alone (and the diagonal), and only they have a scatter map and a colour. An MPI process that fills
  /// its own rows builds the pattern of the elements it assembles, not the whole mesh's.
  ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dofs_per_node,
                 const std::vector<char>& keep);

  const SparseMatrix& pattern() const { return pattern_; }
  int local_size() const { return m_; }
  Index num_elements() const { return ne_; }
  /// Value indices of element e's local entries, column-major (entry (i, j) at [j * m + i]); e must be kept.
  const int* scatter(Index e) const {
    const size_t k = slot_.empty() ? static_cast<size_t>(e) : static_cast<size_t>(slot_[static_cast<size_t>(e)]);
    return scatter_.data() + k * m_ * m_;
  }
  /// Element colours (lists of elements).
  const std::vector<std::vector<Index>>& colors() const { return colors_; }

  /// Adds a column-major local matrix (m x m) of element e into `values` (the value array of a matrix
  /// with pattern()'s structure).
  template <class LocalMatrix>
  void add(Index e, const LocalMatrix& Ke, double* values) const {
    const int* sc = scatter(e);
    for (int j = 0; j < m_; ++j)
      for (int i = 0; i < m_; ++i) values[sc[j * m_ + i]] += Ke(i, j);
  }

  /// Adds a scalar (node by node) local matrix Me (npe x npe) of element e on every one of the dofs_per_node
  /// components, Me (x) I: a mass matrix.
  template <class NodeMatrix>
  void add_per_component(Index e, const NodeMatrix& Me, double* values) const {
    const int* sc = scatter(e);
    const int dpn = m_ / static_cast<int>(Me.rows());
    for (int b = 0; b < Me.cols(); ++b)
      for (int a = 0; a < Me.rows(); ++a)
        for (int d = 0; d < dpn; ++d) values[sc[(dpn * b + d) * m_ + dpn * a + d]] += Me(a, b);
  }

 private:
  void build(const std::vector<Index>& conn, int npe, Index num_nodes, int dpn, const std::vector<Index>& elements);
  int m_ = 0;
  Index ne_ = 0;
  std::vector<Index> slot_;  // with `keep`: each element's place among the kept ones (-1: left out); else empty
  SparseMatrix pattern_;
  std::vector<int> scatter_;
  std::vector<std::vector<Index>> colors_;
};

}  // namespace lagfsi
