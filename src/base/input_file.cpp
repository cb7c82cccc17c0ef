// Reading input files: regular files only, with a size bound (input_file.hpp).
#include <lagfsi/input_file.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <sstream>

namespace lagfsi {

namespace {

std::string kind_of(mode_t m) {
  if (S_ISDIR(m)) return "a folder";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

std::string megabytes(std::uintmax_t bytes) {
  std::ostringstream o;
  o.precision(3);
  o << static_cast<double>(bytes) / (1024.0 * 1024.0) << " MB";
  return o.str();
}

/// Closes the descriptor on every path out.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_regular_file(const std::filesystem::path& file, std::uintmax_t max_bytes) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer before fstat can refuse it.
  Fd f{::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (f.fd < 0) throw InputFileError(std::string("cannot open the file (") + std::strerror(errno) + ")");
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) throw InputFileError(std::string("cannot open the file (") + std::strerror(errno) + ")");
  if (!S_ISREG(st.st_mode)) throw InputFileError("is " + kind_of(st.st_mode) + ", not a regular file");
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  auto too_large = [&](std::uintmax_t n) {
    throw InputFileError("is " + megabytes(n) + ", more than the " + megabytes(max_bytes) +
                         " a file of this kind may have");
  };
  if (size > max_bytes) too_large(size);
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputFileError(std::string("cannot read the file (") + std::strerror(errno) + ")");
    }
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) too_large(text.size());  // a file that grows while it is read
  }
  return text;
}

}  // namespace lagfsi
