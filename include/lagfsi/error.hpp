#pragma once
/// @file error.hpp
/// Errors that end a run with a one-line message and a non-zero exit code.
#include <stdexcept>
#include <string>

namespace lagfsi {

/// Bad input: a case file, a CSV table, a geometry. The message is "FILE: JSON_PATH: reason".
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& path, const std::string& reason)
      : std::runtime_error(file + ": " + (path.empty() ? std::string("/") : path) + ": " + reason),
        file_(file),
        path_(path),
        reason_(reason) {}
  const std::string& file() const { return file_; }
  const std::string& json_path() const { return path_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, path_, reason_;
};

/// An output file that cannot be written (disk full, file-size limit, permissions, a folder in its place).
/// The message is "FILE: cannot write (reason)", naming the file.
class OutputError : public std::runtime_error {
 public:
  OutputError(const std::string& file, const std::string& reason)
      : std::runtime_error(file + ": cannot write (" + reason + ")"), file_(file) {}
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

/// A solve that cannot go on: Newton divergence, non-finite values, a singular matrix.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lagfsi
