// The PETSc backend's matrix (petsc_matrix.hpp): a compressed sparse matrix's rows written into PETSc's own arrays,
// whole or as the four blocks of a saddle-point nest.
#include "petsc_matrix.hpp"

#include <lagfsi/error.hpp>
#include <lagfsi/mpi_run.hpp>

#include <string>

namespace lagfsi::petsc {

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw SolverError(std::string("petsc: ") + what + " failed (" + (text ? text : "PETSc error") + ")");
}

namespace {

/// An AIJ matrix's rows as PETSc keeps them: the diagonal block (the whole of a sequential matrix) with local column
/// numbers, and the off-diagonal one with compressed numbers (garray[] their columns, in increasing order). A row's
/// entries taken in the order of their columns therefore go to the next place of that row in one block or the other.
struct RowArrays {
  Mat d = nullptr, o = nullptr;
  const PetscInt* garray = nullptr;
  const PetscInt *di = nullptr, *dj = nullptr, *oi = nullptr, *oj = nullptr;
  PetscInt dn = 0, on = 0;
  PetscBool dok = PETSC_FALSE, ook = PETSC_FALSE;
  PetscScalar *dv = nullptr, *ov = nullptr;
  PetscInt col_lo = 0, col_hi = 0;  // the diagonal block's columns
  std::vector<PetscInt> nd, no;     // each row's next place in the diagonal and the off-diagonal block

  /// `distributed`: an MPI matrix whose own columns are [lo, lo + cols); `values`: the values open for writing.
  void open(Mat m, bool distributed, PetscInt lo, PetscInt cols, PetscInt global_cols, bool values) {
    if (distributed)
      check(MatMPIAIJGetSeqAIJ(m, &d, &o, &garray), "MatMPIAIJGetSeqAIJ");
    else
      d = m;
    col_lo = distributed ? lo : 0;
    col_hi = distributed ? lo + cols : global_cols;
    check(MatGetRowIJ(d, 0, PETSC_FALSE, PETSC_FALSE, &dn, &di, &dj, &dok), "MatGetRowIJ");
    if (o) check(MatGetRowIJ(o, 0, PETSC_FALSE, PETSC_FALSE, &on, &oi, &oj, &ook), "MatGetRowIJ");
    if (values) {
      check(MatSeqAIJGetArrayWrite(d, &dv), "MatSeqAIJGetArrayWrite");
      if (o) check(MatSeqAIJGetArrayWrite(o, &ov), "MatSeqAIJGetArrayWrite");
    }
    if (dok) nd.assign(di, di + dn);
    if (o && ook) no.assign(oi, oi + on);
  }
  void close() {
    if (dv) check(MatSeqAIJRestoreArrayWrite(d, &dv), "MatSeqAIJRestoreArrayWrite");
    if (ov) check(MatSeqAIJRestoreArrayWrite(o, &ov), "MatSeqAIJRestoreArrayWrite");
    check(MatRestoreRowIJ(d, 0, PETSC_FALSE, PETSC_FALSE, &dn, &di, &dj, &dok), "MatRestoreRowIJ");
    if (o) check(MatRestoreRowIJ(o, 0, PETSC_FALSE, PETSC_FALSE, &on, &oi, &oj, &ook), "MatRestoreRowIJ");
  }
  /// Whether the rows have the lengths of the row pointers `ptr`.
  bool same_rows(const std::vector<PetscInt>& ptr) const {
    const auto m = static_cast<PetscInt>(ptr.size()) - 1;
    if (!dok || dn != m || (o && (!ook || on != m))) return false;
    for (PetscInt r = 0; r < m; ++r)
      if ((di[r + 1] - di[r]) + (o ? oi[r + 1] - oi[r] : 0) !=
          ptr[static_cast<size_t>(r) + 1] - ptr[static_cast<size_t>(r)])
        return false;
    return true;
  }
  /// Whether row r's next entry is at column `col`.
  bool next_is(PetscInt r, PetscInt col) {
    if (col >= col_lo && col < col_hi) {
      const PetscInt at = nd[static_cast<size_t>(r)]++;
      return at < di[r + 1] && dj[at] + col_lo == col;
    }
    if (!o) return false;
    const PetscInt at = no[static_cast<size_t>(r)]++;
    return at < oi[r + 1] && garray[oj[at]] == col;
  }
  /// Row r's next entry (at column col) takes v.
  void put(PetscInt r, PetscInt col, double v) {
    if (col >= col_lo && col < col_hi)
      dv[nd[static_cast<size_t>(r)]++] = v;
    else
      ov[no[static_cast<size_t>(r)]++] = v;
  }
};

}  // namespace

SystemMatrix::SystemMatrix(MPI_Comm comm, int block_size, bool split, std::string prefix)
    : comm_(comm), bs_(block_size), split_(split && block_size >= 2), prefix_(std::move(prefix)) {
  int size = 1;
  MPI_Comm_size(comm_, &size);
  distributed_ = size > 1;
}

void SystemMatrix::destroy() {
  if (mat_) MatDestroy(&mat_);
  for (Block& b : blocks_)
    if (b.mat) MatDestroy(&b.mat);
}

bool SystemMatrix::fill(const SparseMatrix& A, PetscInt lo, PetscInt hi, const std::function<void()>& before_new) {
  local_ = hi - lo;
  if (!split_) return fill_whole(A, lo, hi, before_new);
  switch (bs_) {
    case 3:
      return fill_split<3>(A, lo, hi, before_new);
    case 4:
      return fill_split<4>(A, lo, hi, before_new);
    default:
      return fill_split<0>(A, lo, hi, before_new);
  }
}

bool SystemMatrix::fill_whole(const SparseMatrix& A, PetscInt lo, PetscInt hi,
                              const std::function<void()>& before_new) {
  blocks_.resize(1);
  Block& b = blocks_[0];
  b.rows = b.cols = hi - lo;
  b.row_lo = b.col_lo = lo;
  b.global_rows = b.global_cols = static_cast<PetscInt>(A.rows());
  b.block_size = bs_ > 1 && A.rows() % bs_ == 0 ? bs_ : 1;
  const int* op = A.outerIndexPtr();
  const int* ip = A.innerIndexPtr();
  auto each = [&](const auto& fn) {
    for (Index col = 0; col < A.outerSize(); ++col)
      for (int k = op[col]; k < op[col + 1]; ++k)
        if (ip[k] >= lo && ip[k] < hi) fn(0, static_cast<PetscInt>(ip[k] - lo), static_cast<PetscInt>(col), k);
  };
  return write(A, each, before_new);
}

template <int BS>
bool SystemMatrix::fill_split(const SparseMatrix& A, PetscInt lo, PetscInt hi,
                              const std::function<void()>& before_new) {
  const int bs = BS > 0 ? BS : bs_;  // a constant for the usual sizes: the divisions below become products
  const int nv = bs - 1;             // the first field's unknowns a node
  const PetscInt nodes = static_cast<PetscInt>(A.rows()) / bs, first = lo / bs, m = (hi - lo) / bs;
  blocks_.resize(4);
  for (int g = 0; g < 2; ++g)
    for (int h = 0; h < 2; ++h) {
      Block& b = blocks_[static_cast<size_t>(2 * g + h)];
      b.rows = g == 0 ? nv * m : m;
      b.cols = h == 0 ? nv * m : m;
      b.row_lo = g == 0 ? nv * first : first;
      b.col_lo = h == 0 ? nv * first : first;
      b.global_rows = g == 0 ? nv * nodes : nodes;
      b.global_cols = h == 0 ? nv * nodes : nodes;
      b.block_size = g == 0 && h == 0 ? nv : 1;
    }
  const PetscInt row_lo[2] = {nv * first, first};
  const int* op = A.outerIndexPtr();
  const int* ip = A.innerIndexPtr();
  // Unknown u of node I: the second field if it is the node's last one, at I there; the first at nv I + u % bs.
  auto each = [&](const auto& fn) {
    for (Index col = 0; col < A.outerSize(); ++col) {
      const Index J = col / bs;
      const int d = static_cast<int>(col - J * bs), h = d == nv ? 1 : 0;
      const auto c = static_cast<PetscInt>(h ? J : nv * J + d);
      for (int k = op[col]; k < op[col + 1]; ++k) {
        const Index R = ip[k];
        if (R < lo || R >= hi) continue;
        const Index I = R / bs;
        const int u = static_cast<int>(R - I * bs), g = u == nv ? 1 : 0;
        fn(2 * g + h, static_cast<PetscInt>(g ? I : nv * I + u) - row_lo[g], c, k);
      }
    }
  };
  return write(A, each, before_new);
}

template <class Each>
bool SystemMatrix::write(const SparseMatrix& A, const Each& each, const std::function<void()>& before_new) {
  // The pattern of A's rows, block by block.
  for (Block& b : blocks_) b.ptr.assign(static_cast<size_t>(b.rows) + 1, 0);
  each([&](int i, PetscInt r, PetscInt, int) { ++blocks_[static_cast<size_t>(i)].ptr[static_cast<size_t>(r) + 1]; });
  for (Block& b : blocks_)
    for (size_t r = 1; r < b.ptr.size(); ++r) b.ptr[r] += b.ptr[r - 1];
  // The same pattern as the matrix's own (compared with PETSc's arrays, not with a copy of them).
  std::vector<RowArrays> rows(blocks_.size());
  auto open = [&](bool values) {
    for (size_t i = 0; i < blocks_.size(); ++i) {
      const Block& b = blocks_[i];
      rows[i].open(b.mat, distributed_, b.col_lo, b.cols, b.global_cols, values);
    }
  };
  auto close = [&] {
    for (RowArrays& a : rows) a.close();
  };
  int same = mat_ != nullptr;
  if (same) {
    open(false);
    for (size_t i = 0; i < blocks_.size(); ++i) same = same && rows[i].same_rows(blocks_[i].ptr);
    if (same)
      each([&](int i, PetscInt r, PetscInt col, int) { same = same && rows[static_cast<size_t>(i)].next_is(r, col); });
    close();
  }
  // Making the matrix is collective: every process takes the same branch.
  if (distributed_) {
    const double t0 = MPI_Wtime();
    MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_MIN, comm_);
    mpi_run::note_traffic(MPI_Wtime() - t0, mpi_run::allreduce_bytes(sizeof same));
  }
  if (!same) {
    if (before_new) before_new();
    destroy();  // the old matrix let go before the new one is made
    std::vector<std::vector<PetscInt>> cols(blocks_.size()), next(blocks_.size());
    for (size_t i = 0; i < blocks_.size(); ++i) {
      cols[i].resize(static_cast<size_t>(blocks_[i].ptr.back()));
      next[i].assign(blocks_[i].ptr.begin(), blocks_[i].ptr.end() - 1);
    }
    each([&](int i, PetscInt r, PetscInt col, int) {
      const auto b = static_cast<size_t>(i);
      cols[b][static_cast<size_t>(next[b][static_cast<size_t>(r)]++)] = col;
    });
    for (size_t i = 0; i < blocks_.size(); ++i) {
      make_block(blocks_[i], cols[i]);
      std::vector<PetscInt>().swap(cols[i]);
    }
    make_operator();
  }
  // The values straight into PETSc's arrays.
  const double* vp = A.valuePtr();
  open(true);
  each([&](int i, PetscInt r, PetscInt col, int k) { rows[static_cast<size_t>(i)].put(r, col, vp[k]); });
  close();
  // Writing the arrays marks a sequential matrix as changed, not a distributed one or a nest: an assembly with no
  // entries to move does (and, for a nest, its blocks).
  if (distributed_ || split_) {
    check(MatAssemblyBegin(mat_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(mat_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }
  return !same;
}

void SystemMatrix::make_block(Block& b, const std::vector<PetscInt>& cols) {
  check(MatCreate(comm_, &b.mat), "MatCreate");
  check(MatSetSizes(b.mat, b.rows, b.cols, b.global_rows, b.global_cols), "MatSetSizes");
  check(MatSetType(b.mat, MATAIJ), "MatSetType");
  if (b.block_size > 1) check(MatSetBlockSize(b.mat, b.block_size), "MatSetBlockSize");
  check(MatSetOptionsPrefix(b.mat, prefix_.c_str()), "MatSetOptionsPrefix");
  check(MatSeqAIJSetPreallocationCSR(b.mat, b.ptr.data(), cols.data(), nullptr), "MatSeqAIJSetPreallocationCSR");
  check(MatMPIAIJSetPreallocationCSR(b.mat, b.ptr.data(), cols.data(), nullptr), "MatMPIAIJSetPreallocationCSR");
  check(MatSetOption(b.mat, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
}

void SystemMatrix::make_operator() {
  if (!split_) {
    mat_ = blocks_[0].mat;
    check(PetscObjectReference(reinterpret_cast<PetscObject>(mat_)), "PetscObjectReference");
    return;
  }
  Mat m[4] = {blocks_[0].mat, blocks_[1].mat, blocks_[2].mat, blocks_[3].mat};
  check(MatCreateNest(comm_, 2, nullptr, 2, nullptr, m, &mat_), "MatCreateNest");
  check(MatSetOptionsPrefix(mat_, prefix_.c_str()), "MatSetOptionsPrefix");
}

void SystemMatrix::field_sets(IS sets[2]) const {
  sets[0] = sets[1] = nullptr;
  if (split_ && mat_) check(MatNestGetISs(mat_, sets, nullptr), "MatNestGetISs");
}

template <class Fn>
void SystemMatrix::each_place(const Fn& fn) const {
  if (!split_) {
    for (PetscInt k = 0; k < local_; ++k) fn(k, k);
    return;
  }
  // The nest's order: this process's velocities (nv a node, node by node), then its pressures.
  const PetscInt nv = bs_ - 1, m = local_ / bs_;
  for (PetscInt i = 0; i < m; ++i) {
    for (PetscInt c = 0; c < nv; ++c) fn(bs_ * i + c, nv * i + c);
    fn(bs_ * i + nv, nv * m + i);
  }
}

void SystemMatrix::to_petsc(const double* v, PetscScalar* p) const {
  each_place([&](PetscInt k, PetscInt q) { p[q] = v[k]; });
}

void SystemMatrix::from_petsc(const PetscScalar* p, double* v) const {
  each_place([&](PetscInt k, PetscInt q) { v[k] = p[q]; });
}

}  // namespace lagfsi::petsc
