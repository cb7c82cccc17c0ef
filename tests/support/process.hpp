#pragma once
// Running the lagfsi executable as a child process without a shell: arguments passed as they are (bytes that
// are not UTF-8, 100 000-character keys), stdout and stderr to files, an optional file-size limit
// (RLIMIT_FSIZE: a full disk without a small file system), and the child's pid for sending it signals.
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace lagfsi::testing {

struct Spawned {
  pid_t pid = -1;
  std::filesystem::path out_file, err_file;
};

/// Starts `lagfsi args...` with stdout to `out_file` and stderr to `err_file`; `fsize_limit` >= 0 sets
/// RLIMIT_FSIZE (bytes) in the child.
inline Spawned spawn_lagfsi(const std::vector<std::string>& args, const std::filesystem::path& out_file,
                            const std::filesystem::path& err_file, long long fsize_limit = -1) {
  Spawned s{-1, out_file, err_file};
  s.pid = ::fork();
  if (s.pid == 0) {
    const int e = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int o = out_file == "/dev/full" ? ::open("/dev/full", O_WRONLY)
                                          : ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (e < 0 || o < 0) ::_exit(126);
    ::dup2(e, 2);
    ::dup2(o, 1);
    if (fsize_limit >= 0) {
      rlimit rl{static_cast<rlim_t>(fsize_limit), static_cast<rlim_t>(fsize_limit)};
      ::setrlimit(RLIMIT_FSIZE, &rl);
    }
    std::vector<std::string> all{LAGFSI_EXE};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(LAGFSI_EXE, argv.data());
    ::_exit(127);
  }
  return s;
}

/// Waits for the child: its exit code, or 1000 + the signal that killed it.
inline int wait_exit(const Spawned& s) {
  int status = 0;
  while (::waitpid(s.pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 1000 + WTERMSIG(status);
  return -1;
}

inline std::string file_text(const std::filesystem::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Finished {
  int code;
  std::string out, err;
};

/// Runs `lagfsi args...` to the end; stdout and stderr in `dir`.
inline Finished run_args(const std::vector<std::string>& args, const std::filesystem::path& dir,
                         long long fsize_limit = -1) {
  const Spawned s = spawn_lagfsi(args, dir / "stdout.txt", dir / "stderr.txt", fsize_limit);
  const int code = wait_exit(s);
  return {code, file_text(dir / "stdout.txt"), file_text(dir / "stderr.txt")};
}

inline long count_lines(const std::string& s) { return static_cast<long>(std::count(s.begin(), s.end(), '\n')); }

}  // namespace lagfsi::testing
