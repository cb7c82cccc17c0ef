#pragma once
/// @file app.hpp
/// The `lagfsi` command line as a library function (so tests can call it in-process).
namespace lagfsi {
/// Runs the command line; returns the process exit code. Never throws.
int app_main(int argc, char** argv);
}  // namespace lagfsi
