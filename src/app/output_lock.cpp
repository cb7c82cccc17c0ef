// The output folder's lock (output_lock.hpp).
#include "output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <string>

namespace lagfsi {

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  // Removed while still held: a run that opens the file now either locks the old inode after this close
  // (and notices it is gone, see acquire) or creates a new file.
  ::unlink(file_.c_str());
  ::close(fd_);
}

std::string OutputLock::acquire(const std::filesystem::path& dir) {
  file_ = dir / kLockFileName;
  // A file left by a run that was killed (SIGKILL, power loss) holds no lock: the kernel released it with the
  // process, so it is taken over whatever process id it names. A file that the run holding it removed between
  // our open and our flock is not the lock any more: open it again.
  for (int attempt = 0; attempt < 10; ++attempt) {
    fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) return "cannot create " + file_.string() + " (" + std::strerror(errno) + ")";
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
      return "cannot lock " + file_.string() + " (" + std::strerror(err) + ")";
    }
    struct stat held {
    }, now{};
    if (::fstat(fd_, &held) == 0 && ::stat(file_.c_str(), &now) == 0 && held.st_ino == now.st_ino &&
        held.st_dev == now.st_dev)
      break;
    ::close(fd_);
    fd_ = -1;
  }
  if (fd_ < 0) return "cannot lock " + file_.string() + " (it keeps being replaced)";
  // The holder's process id, for the message of the next run that finds the folder locked.
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size()))
    return "cannot write " + file_.string() + " (" + std::strerror(errno) + ")";
  return "";
}

}  // namespace lagfsi
