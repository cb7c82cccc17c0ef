#pragma once
/// @file input_file.hpp
/// Reading an input file (a case file, a table): only a regular file is read, and only up to a size bound,
/// so that a FIFO, a device (/dev/zero, /dev/urandom), a folder or a file of gigabytes is refused at once
/// instead of blocking or filling the memory.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace lagfsi {

/// Why an input file could not be read (the reason only; the caller names the file).
class InputFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Case files: at most 16 MiB. Tables: at most 256 MiB.
inline constexpr std::uintmax_t kMaxCaseFileBytes = std::uintmax_t{16} << 20;
inline constexpr std::uintmax_t kMaxTableFileBytes = std::uintmax_t{256} << 20;

/// The whole content of `file`, which must be a regular file (symbolic links followed) of at most
/// `max_bytes` bytes; throws InputFileError ("cannot open the file (No such file or directory)", "is a
/// FIFO, not a regular file", "is 2.1 GB, more than the 16 MB a file of this kind may have", ...).
std::string read_regular_file(const std::filesystem::path& file, std::uintmax_t max_bytes);

}  // namespace lagfsi
