#pragma once
// SIGINT and SIGTERM during a run (interrupt.cpp): the handler only records the signal; the driver ends the
// current step, writes the output and summary.json ("interrupted") and exits with 128 + the signal's number.
// A second signal of the same kind ends the process at once (the handlers are reset on first use).
namespace lagfsi {

class InterruptGuard {
 public:
  /// Installs the handlers (and ignores SIGXFSZ, so that a write beyond the file-size limit fails with EFBIG
  /// and is reported instead of killing the process).
  InterruptGuard();
  /// Restores the previous handlers.
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  /// The signal received since construction (SIGINT or SIGTERM), or 0.
  static int received();
};

/// "SIGINT", "SIGTERM".
const char* signal_name(int sig);

}  // namespace lagfsi
