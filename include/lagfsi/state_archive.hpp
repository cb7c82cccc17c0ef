#pragma once
/// @file state_archive.hpp
/// The state of a run in binary form, for checkpoints (`output.checkpoint`) and `lagfsi run --restart`
/// (docs/running.md). One method per class, serialize(StateArchive& ar), names every field that the time loop
/// needs to continue bit for bit; the same method writes (ar.loading() false) and reads (true) them, so the
/// two directions cannot drift apart. Numbers are stored as their bytes (the checkpoint is read back by the
/// same build on the same machine), containers with their sizes.
///
///   void Foo::serialize(StateArchive& ar) {
///     ar.section("foo");          // a named marker: reading it back checks that the fields are in step
///     ar.io(x_, v_, steps_);      // Vec, Vec, long
///     series_.serialize(ar);      // a member's own serialize
///   }
///
/// Reading past the end or a marker that differs throws CheckpointError.
#include <lagfsi/types.hpp>

#include <array>
#include <cstdint>
#include <cstring>
#include <deque>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace lagfsi {

/// A checkpoint that cannot be read (truncated, from another version, fields out of step).
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class StateArchive {
 public:
  /// An empty archive to write into.
  StateArchive() = default;
  /// An archive that reads `data` (what data() of a writing archive returned).
  explicit StateArchive(std::string data) : loading_(true), buf_(std::move(data)) {}

  bool loading() const { return loading_; }
  const std::string& data() const { return buf_; }
  /// Reading: every byte has been read.
  bool at_end() const { return pos_ == buf_.size(); }

  /// A named marker (written as text; reading checks it).
  void section(const std::string& name);

  template <class T>
  requires std::is_arithmetic_v<T> || std::is_enum_v<T>
  void io(T& v) { raw(&v, sizeof v); }
  void io(std::string& s);
  /// Eigen vectors and matrices of doubles, fixed or dynamic size.
  template <int R, int C, int O, int MR, int MC>
  void io(Eigen::Matrix<double, R, C, O, MR, MC>& m) {
    Eigen::Index rows = m.rows(), cols = m.cols();
    io(rows);
    io(cols);
    if (loading_) {
      if (rows < 0 || cols < 0 || (R != Eigen::Dynamic && rows != R) || (C != Eigen::Dynamic && cols != C))
        throw CheckpointError("a matrix of the wrong size");
      check_left(static_cast<size_t>(rows * cols) * sizeof(double));
      m.resize(rows, cols);
    }
    raw(m.data(), static_cast<size_t>(rows * cols) * sizeof(double));
  }
  template <class T>
  void io(std::vector<T>& v) {
    std::uint64_t n = v.size();
    io(n);
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      if (loading_) {
        check_left(n * sizeof(T));
        v.resize(n);
      }
      raw(v.data(), n * sizeof(T));
    } else {
      if (loading_) {
        check_left(n);  // every element takes at least a byte
        v.resize(n);
      }
      for (auto& e : v) io(e);
    }
  }
  template <class T>
  void io(std::deque<T>& d) {
    std::uint64_t n = d.size();
    io(n);
    if (loading_) {
      check_left(n);
      d.resize(n);
    }
    for (auto& e : d) io(e);
  }
  template <class T, size_t N>
  void io(std::array<T, N>& a) {
    for (auto& e : a) io(e);
  }
  template <class A, class B>
  void io(std::pair<A, B>& p) {
    io(p.first);
    io(p.second);
  }
  /// Several fields in order.
  template <class T, class U, class... More>
  void io(T& a, U& b, More&... more) {
    io(a);
    io(b, more...);
  }

 private:
  void raw(void* p, size_t n);
  void check_left(std::uint64_t n) const;
  bool loading_ = false;
  std::string buf_;
  size_t pos_ = 0;
};

}  // namespace lagfsi
