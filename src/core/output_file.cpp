// Checked output files (output_file.hpp): POSIX descriptors, so that every failed write is seen with its errno
// (std::ofstream reports a failed flush without a reason, or not at all when its destructor flushes).
#include <lagfsi/output_file.hpp>

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

namespace lagfsi {

namespace fs = std::filesystem;

namespace {

/// Writes all of `text` to `fd`; returns 0 or the errno of the failed write.
int write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    text.remove_prefix(static_cast<size_t>(n));
  }
  return 0;
}

int open_for_writing(const fs::path& path) {
  for (;;) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd >= 0 || errno != EINTR) return fd;
  }
}

}  // namespace

std::string errno_reason(int e) { return std::strerror(e); }

void write_file_atomic(const fs::path& path, std::string_view text) {
  fs::path tmp = path;
  tmp += ".tmp";
  const int fd = open_for_writing(tmp);
  if (fd < 0) throw OutputError(path.string(), errno_reason(errno));
  int err = write_all(fd, text);
  // close() reports what a network or quota-limited file system could not store.
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) {
    ::unlink(tmp.c_str());
    throw OutputError(path.string(), errno_reason(err));
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    ::unlink(tmp.c_str());
    throw OutputError(path.string(), ec.message());
  }
}

AppendFile::~AppendFile() {
  if (fd_ >= 0) ::close(fd_);
}

void AppendFile::open(const fs::path& path) {
  if (fd_ >= 0) ::close(fd_);
  path_ = path;
  fd_ = open_for_writing(path);
  if (fd_ < 0) throw OutputError(path.string(), errno_reason(errno));
  size_ = 0;
}

void AppendFile::resume(const fs::path& path, std::uint64_t size) {
  if (fd_ >= 0) ::close(fd_);
  path_ = path;
  fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0) throw OutputError(path.string(), errno_reason(errno));
  if (::ftruncate(fd_, static_cast<off_t>(size)) != 0 || ::lseek(fd_, 0, SEEK_END) < 0)
    throw OutputError(path.string(), errno_reason(errno));
  size_ = size;
}

void AppendFile::write(std::string_view text) {
  if (fd_ < 0) throw OutputError(path_.string(), "the file is not open");
  const int err = write_all(fd_, text);
  if (err != 0) throw OutputError(path_.string(), errno_reason(err));
  size_ += text.size();
}

}  // namespace lagfsi
