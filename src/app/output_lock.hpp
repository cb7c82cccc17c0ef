#pragma once
// The lock of an output folder (output_lock.cpp): a run holds an exclusive flock(2) on OUTDIR/.lagfsi.lock for
// its whole life, so that a second run into the same folder fails at once instead of interleaving its rows
// with the first one's. The run removes the file when it ends (on every path: completed, failed, interrupted);
// the lock itself goes with the process, so the file left by a killed run (SIGKILL) blocks nobody.
#include <filesystem>
#include <string>

namespace lagfsi {

class OutputLock {
 public:
  OutputLock() = default;
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  /// Locks `dir` (which must exist). Returns "" or why not ("in use by another lagfsi run (process 1234)").
  std::string acquire(const std::filesystem::path& dir);

 private:
  int fd_ = -1;
  std::filesystem::path file_;
};

/// The lock file's name (reserved: no output file may have it).
inline constexpr const char* kLockFileName = ".lagfsi.lock";

}  // namespace lagfsi
