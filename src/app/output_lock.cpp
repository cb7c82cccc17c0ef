// The output folder's lock (output_lock.hpp).
#include "output_lock.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <sys/file.h>
#include <unistd.h>

namespace lagfsi {

OutputLock::~OutputLock() {
  if (fd_ >= 0) ::close(fd_);   // releases the lock
}

std::string OutputLock::acquire(const std::filesystem::path& dir) {
  const std::filesystem::path file = dir / kLockFileName;
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) return "cannot create " + file.string() + " (" + std::strerror(errno) + ")";
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    char pid[32] = {0};
    const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
    std::string holder = n > 0 ? std::string(pid, static_cast<size_t>(n)) : std::string();
    while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' ')) holder.pop_back();
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK)
      return "in use by another lagfsi run" + (holder.empty() ? std::string() : " (process " + holder + ")") +
             ": wait for it to end or give another folder with -o";
    return "cannot lock " + file.string() + " (" + std::strerror(err) + ")";
  }
  // The holder's process id, for the message of the next run that finds the folder locked.
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size()))
    return "cannot write " + file.string() + " (" + std::strerror(errno) + ")";
  return "";
}

}  // namespace lagfsi
