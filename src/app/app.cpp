#include <lagfsi/analysis.hpp>
#include <lagfsi/app.hpp>

#include <Eigen/Core>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace lagfsi {

namespace {

const char* kUsageText =
    "usage: lagfsi run CASE.json [-o OUTDIR] [--set key.path=value ...] [--threads N] [--quiet]\n"
    "       lagfsi check CASE.json [--set key.path=value ...]\n"
    "       lagfsi --version | --help\n";

const char* kHelp =
    "lagfsi: 2D Lagrangian mechanics (positional FEM solids, PFEM free-surface fluid; FSI to come).\n\n"
    "commands:\n"
    "  run CASE.json     run a case; writes OUTDIR/{resolved_case.json, <body>.pvd, <body>/*.vtu,\n"
    "                    probes.csv, log.csv, summary.json} (OUTDIR defaults to out/<case name>)\n"
    "  check CASE.json   validate a case (meshes and models are built) and print it with every\n"
    "                    default filled in; runs nothing\n\n"
    "options:\n"
    "  -o, --output DIR        output folder\n"
    "  --set key.path=value    override a case value (e.g. --set analysis.dt=1e-4,\n"
    "                          --set bodies.0.mesh.size=0.01); the value is JSON or a plain string\n"
    "  --threads N             OpenMP threads for assembly\n"
    "  --quiet                 no per-step progress line on stderr\n\n"
    "exit codes: 0 ok, 1 usage, 2 bad input, 3 solver failure (divergence), 4 internal error\n";

}  // namespace

int app_main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::cerr << kUsageText;
    return kUsage;
  }
  const std::string cmd = args[0];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::cout << kUsageText << "\n" << kHelp;
    return kOk;
  }
  if (cmd == "--version") {
    std::cout << "lagfsi " << LAGFSI_VERSION << " (commit " << LAGFSI_GIT_COMMIT << ")\n"
              << "  Eigen " << EIGEN_WORLD_VERSION << "." << EIGEN_MAJOR_VERSION << "." << EIGEN_MINOR_VERSION
              << ", SuiteSparse " << LAGFSI_SUITESPARSE_VERSION << ", VTK " << LAGFSI_VTK_VERSION << ", CGAL "
              << LAGFSI_CGAL_VERSION << "\n";
    return kOk;
  }
  if (cmd != "run" && cmd != "check") {
    std::cerr << "lagfsi: error: unknown command '" << cmd << "'\n" << kUsageText;
    return kUsage;
  }
  RunOptions opt;
  for (size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](const char* what) -> std::string {
      if (i + 1 >= args.size()) {
        std::cerr << "lagfsi: error: " << a << " needs " << what << "\n";
        throw 1;
      }
      return args[++i];
    };
    try {
      if (a == "-o" || a == "--output") {
        opt.out_dir = value("a folder");
      } else if (a == "--set") {
        opt.overrides.push_back(value("key.path=value"));
      } else if (a.rfind("--set=", 0) == 0) {
        opt.overrides.push_back(a.substr(6));
      } else if (a == "--threads") {
        const std::string v = value("a number");
        size_t used = 0;
        try {
          opt.threads = std::stoi(v, &used);
        } catch (...) {
          opt.threads = -1;
        }
        if (used != v.size()) opt.threads = -1;   // "1x", "2 threads"
        if (opt.threads < 1) {
          std::cerr << "lagfsi: error: --threads needs a positive integer (got '" << v << "')\n";
          return kUsage;
        }
      } else if (a == "--quiet" || a == "-q") {
        opt.quiet = true;
      } else if (!a.empty() && a[0] == '-') {
        std::cerr << "lagfsi: error: unknown option '" << a << "'\n" << kUsageText;
        return kUsage;
      } else if (opt.case_file.empty()) {
        opt.case_file = a;
      } else {
        std::cerr << "lagfsi: error: unexpected argument '" << a << "'\n" << kUsageText;
        return kUsage;
      }
    } catch (int) {
      return kUsage;
    }
  }
  if (opt.case_file.empty()) {
    std::cerr << "lagfsi: error: " << cmd << " needs a case file\n" << kUsageText;
    return kUsage;
  }
  return cmd == "run" ? run_case(opt) : check_case(opt);
}

}  // namespace lagfsi
