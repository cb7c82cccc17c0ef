#pragma once
/// @file output_file.hpp
/// Output files whose every write is checked: a failed write (disk full, file-size limit, a read-only or
/// vanished folder) throws OutputError naming the file, so that a run never reports success over output
/// that was cut off.
#include <lagfsi/error.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace lagfsi {

/// Writes `text` to `path` through `path`.tmp and a rename: a reader sees the old file or the whole new one.
void write_file_atomic(const std::filesystem::path& path, std::string_view text);

/// A file written sequentially (log.csv, probes.csv): created (or truncated) by open(), each write() checked
/// and handed to the operating system at once (nothing buffered in the process).
class AppendFile {
 public:
  AppendFile() = default;
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;
  ~AppendFile();
  void open(const std::filesystem::path& path);
  /// Opens an existing file cut back to its first `size` bytes, to write on after them (a restart).
  void resume(const std::filesystem::path& path, std::uint64_t size);
  /// Bytes written into the file so far (its size).
  std::uint64_t size() const { return size_; }
  void write(std::string_view text);
  bool is_open() const { return fd_ >= 0; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

/// The reason for errno `e` ("No space left on device").
std::string errno_reason(int e);

}  // namespace lagfsi
