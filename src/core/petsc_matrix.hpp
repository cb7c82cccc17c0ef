#pragma once
/// @file petsc_matrix.hpp
/// The matrix of the PETSc backend (petsc_solver.cpp; private to the core, like every PETSc type): a compressed
/// sparse matrix's rows written straight into PETSc's own storage, with no copy of them kept.
///
/// Two layouts:
///  - whole: one AIJ matrix in the system's numbering;
///  - split: a saddle-point system with interleaved unknowns (block_size per node, the last one the pressure) as a
///    nest of four AIJ blocks, [A B^T; C D] with A the first block_size - 1 unknowns of every node (in node order)
///    and D the last ones. A Schur field split then uses the blocks themselves (MatCreateSubMatrix of a nest
///    block is that block), where on one AIJ matrix it extracts a copy of all four: a third less memory for the
///    operator and its preconditioner's blocks together. The vectors keep the nest's order (each process's
///    velocities, then its pressures); to_petsc and from_petsc permute.
/// On several processes each process writes the rows of the nodes it owns (whole blocks of block_size rows: PETSc's
/// default split, PetscSplitOwnership over the nodes).
#include <lagfsi/types.hpp>

#include <petscmat.h>

#include <functional>
#include <string>
#include <vector>

namespace lagfsi::petsc {

/// Throws SolverError with PETSc's text for a non-zero error code ("petsc: <what> failed (<text>)").
void check(PetscErrorCode code, const char* what);

class SystemMatrix {
 public:
  /// A matrix on `comm` for systems of block_size unknowns a node; `split`: the nest layout (block_size >= 2);
  /// `prefix`: the options prefix of the matrices.
  SystemMatrix(MPI_Comm comm, int block_size, bool split, std::string prefix);
  ~SystemMatrix() { destroy(); }
  SystemMatrix(const SystemMatrix&) = delete;
  SystemMatrix& operator=(const SystemMatrix&) = delete;

  /// Writes this process's rows [lo, hi) of A (compressed, stored by columns; the other rows are not read) into the
  /// matrix. Returns true when the pattern was new: the matrix was made again (the old one let go first), and its
  /// solver must take it anew; false when only the values changed (the matrix is then marked as changed).
  /// `before_new` runs before a new matrix is made (to let the solver of the old one go first). Collective.
  bool fill(const SparseMatrix& A, PetscInt lo, PetscInt hi, const std::function<void()>& before_new = {});
  /// The operator (an AIJ or a nest matrix), nullptr before the first fill.
  Mat mat() const { return mat_; }
  bool split() const { return split_; }
  /// The nest's index sets of the two fields (velocity, pressure), for the field split.
  void field_sets(IS sets[2]) const;
  /// This process's entries [lo, hi) of a system vector `v` (v points at entry lo) into PETSc's local array `p`,
  /// in the matrix's order, and back.
  void to_petsc(const double* v, PetscScalar* p) const;
  void from_petsc(const PetscScalar* p, double* v) const;
  /// Lets the matrix go.
  void destroy();

 private:
  /// One AIJ matrix of the layout: this process's rows, and the pattern being compared or made.
  struct Block {
    Mat mat = nullptr;
    PetscInt rows = 0, cols = 0;      // this process's rows and columns
    PetscInt row_lo = 0, col_lo = 0;  // the first of them (in the block's numbering)
    PetscInt global_rows = 0, global_cols = 0;
    PetscInt block_size = 1;
    std::vector<PetscInt> ptr;  // the new pattern's row pointers
  };
  using Hook = std::function<void()>;
  template <int BS>
  bool fill_split(const SparseMatrix& A, PetscInt lo, PetscInt hi, const Hook& before_new);
  bool fill_whole(const SparseMatrix& A, PetscInt lo, PetscInt hi, const Hook& before_new);
  /// Compares the blocks' patterns with the counted rows and A's columns (`each(fn)` calls fn(block, local row,
  /// block column, entry k) for every entry of this process's rows, each row's columns increasing), makes the
  /// blocks again when they differ on any process, then writes A's values. Returns whether they were made again.
  template <class Each>
  bool write(const SparseMatrix& A, const Each& each, const Hook& before_new);
  void make_block(Block& b, const std::vector<PetscInt>& cols);
  /// fn(k, q) for each of this process's system entries: k its place in the system's (interleaved) order, q in the
  /// matrix's.
  template <class Fn>
  void each_place(const Fn& fn) const;
  void make_operator();

  MPI_Comm comm_;
  int bs_;
  bool split_;
  std::string prefix_;
  bool distributed_ = false;
  std::vector<Block> blocks_;  // one, or the four of the nest in row-major order
  Mat mat_ = nullptr;
  PetscInt local_ = 0;  // this process's rows of the system
};

}  // namespace lagfsi::petsc
