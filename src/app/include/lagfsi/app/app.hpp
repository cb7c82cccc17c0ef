#pragma once
/// @file app.hpp
/// The `lagfsi` command line as a library function (so tests can call it in-process).
namespace lagfsi {
/// Runs the command line; returns the process exit code. Never throws. `git_commit`: the sources' commit, for
/// `lagfsi --version` (the executable passes the one it was built from, generated at build time).
int app_main(int argc, char** argv, const char* git_commit = "unknown");
}  // namespace lagfsi
