#pragma once
/// @file assembly.hpp
/// Sparse assembly on a fixed pattern: the CSC pattern of a mesh with `dofs_per_node` unknowns per node
/// (dof = dofs_per_node * node + component), and for each element where its local entries sit in the value array
/// (the "scatter map"), so that assembling a local matrix is a sequence of indexed additions. Elements are
/// coloured (no two elements of a colour share a node; unless built with Colouring::none) so that OpenMP threads
/// can add whole elements without atomics.
///
/// The map is stored per node pair, not per entry: column d n + c of node n holds, for each neighbour m of n in
/// order, its d rows (d = dofs_per_node), so the entry of row d m + r in that column sits at
///   base(n, m) + c s(n) + r,   base(n, m) = outer(d n) + d k(n, m),   s(n) = d (neighbours of n),
/// k(n, m) the place of m among n's neighbours. An element keeps its npe^2 bases and its npe strides s: with
/// d = 3 a triangle's map is 12 integers instead of its 81 entries.
#include <lagfsi/types.hpp>

#include <utility>
#include <vector>

namespace lagfsi {

class ElementPattern {
 public:
  /// Whether the elements are coloured (colors()): the OpenMP loops that add whole elements by colour need it,
  /// a loop that adds into per-thread copies does not.
  enum class Colouring { colour, none };
  ElementPattern() = default;
  /// conn: npe node indices per element; num_nodes: nodes of the mesh (nodes in no element get a
  /// diagonal entry so that the matrix stays square and can carry a Dirichlet 1 on them).
  ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dofs_per_node,
                 Colouring colouring = Colouring::colour);
  /// Only the elements e with keep[e] != 0 (keep has one entry per element of conn): the pattern has their
  /// entries alone (and the diagonal), and only they have a scatter map and a colour. An MPI process that fills
  /// its own rows builds the pattern of the elements it assembles, not the whole mesh's.
  ElementPattern(const std::vector<Index>& conn, int npe, Index num_nodes, int dofs_per_node,
                 const std::vector<char>& keep, Colouring colouring = Colouring::colour);

  ElementPattern(const ElementPattern&) = default;
  ElementPattern& operator=(const ElementPattern&) = default;
  /// Moves hand the arrays over (Eigen's sparse matrices have no move operations of their own: they would copy).
  ElementPattern(ElementPattern&& o) noexcept { *this = std::move(o); }
  ElementPattern& operator=(ElementPattern&& o) noexcept {
    std::swap(m_, o.m_);
    std::swap(npe_, o.npe_);
    std::swap(dpn_, o.dpn_);
    std::swap(per_element_, o.per_element_);
    std::swap(ne_, o.ne_);
    std::swap(colour_, o.colour_);
    slot_.swap(o.slot_);
    pattern_.swap(o.pattern_);
    scatter_.swap(o.scatter_);
    colors_.swap(o.colors_);
    return *this;
  }

  const SparseMatrix& pattern() const { return pattern_; }
  /// The pattern's matrix handed to a caller that fills its values (target's old arrays freed): the scatter map
  /// keeps indexing them, and pattern() is empty afterwards (one copy of the structure instead of two).
  void take_pattern(SparseMatrix& target) {
    target.swap(pattern_);
    SparseMatrix().swap(pattern_);
  }
  int local_size() const { return m_; }
  Index num_elements() const { return ne_; }
  /// One unknown per node: the value indices of element e's local entries, column-major (entry (i, j) at
  /// [j * npe + i]); e must be kept. With more unknowns per node, use position() or add().
  const int* scatter(Index e) const { return map(e); }
  /// The value index of element e's local entry (i, j), i and j local dofs (dofs_per_node * local node + component).
  int position(Index e, int i, int j) const {
    const int* sc = map(e);
    const int a = j / dpn_, b = i / dpn_;
    return sc[a * npe_ + b] + (j % dpn_) * stride(sc, a) + i % dpn_;
  }
  /// Element colours (lists of elements); empty when built with Colouring::none.
  const std::vector<std::vector<Index>>& colors() const { return colors_; }

  /// Adds a column-major local matrix (m x m) of element e into `values` (the value array of a matrix
  /// with pattern()'s structure).
  template <class LocalMatrix>
  void add(Index e, const LocalMatrix& Ke, double* values) const {
    const int* sc = map(e);
    for (int a = 0; a < npe_; ++a)
      for (int cj = 0; cj < dpn_; ++cj) {
        const int j = a * dpn_ + cj, column = cj * stride(sc, a);
        for (int b = 0; b < npe_; ++b) {
          double* v = values + sc[a * npe_ + b] + column;
          for (int ci = 0; ci < dpn_; ++ci) v[ci] += Ke(b * dpn_ + ci, j);
        }
      }
  }

  /// Adds a scalar (node by node) local matrix Me (npe x npe) of element e on every one of the dofs_per_node
  /// components, Me (x) I: a mass matrix.
  template <class NodeMatrix>
  void add_per_component(Index e, const NodeMatrix& Me, double* values) const {
    const int* sc = map(e);
    for (int b = 0; b < npe_; ++b) {
      const int s = stride(sc, b);
      for (int a = 0; a < npe_; ++a)
        for (int d = 0; d < dpn_; ++d) values[sc[b * npe_ + a] + d * s + d] += Me(a, b);
    }
  }

 private:
  /// Element e's map: npe^2 bases (node pair (a, b) at [a npe + b], a the column's node), then, with more than one
  /// unknown per node, npe strides.
  const int* map(Index e) const {
    const size_t k = slot_.empty() ? static_cast<size_t>(e) : static_cast<size_t>(slot_[static_cast<size_t>(e)]);
    return scatter_.data() + k * per_element_;
  }
  int stride(const int* sc, int a) const { return dpn_ > 1 ? sc[npe_ * npe_ + a] : 0; }
  void build(const std::vector<Index>& conn, int npe, Index num_nodes, int dpn, const std::vector<Index>& elements);
  int m_ = 0, npe_ = 0, dpn_ = 0;
  size_t per_element_ = 0;  // integers of an element's map
  Index ne_ = 0;
  bool colour_ = true;
  std::vector<Index> slot_;  // with `keep`: each element's place among the kept ones (-1: left out); else empty
  SparseMatrix pattern_;
  std::vector<int> scatter_;
  std::vector<std::vector<Index>> colors_;
};

}  // namespace lagfsi
