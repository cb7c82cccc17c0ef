#include "progress.hpp"

#include <lagfsi/app/analysis.hpp>
#include <lagfsi/app/app.hpp>
#include <lagfsi/case.hpp>
#include <lagfsi/mpi_run.hpp>
#include <lagfsi/params.hpp>
#include <lagfsi/text.hpp>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

namespace lagfsi {

namespace {

const char* kUsageText =
    "usage: lagfsi run CASE.json [-o OUTDIR] [--set key.path=value ...] [--threads N] [--quiet]\n"
    "                            [--progress auto|bar|lines|none] [--restart OUTDIR] [--stop-after-step K]\n"
    "                            [--max-nodes N]\n"
    "       lagfsi check CASE.json [--set key.path=value ...] [--max-nodes N]\n"
    "       lagfsi keys\n"
    "       lagfsi --version | --help | COMMAND --help\n";

const char* kHelp =
    "lagfsi: 2D Lagrangian mechanics (positional FEM solids and shells, PFEM free-surface fluid, FSI, MPM).\n\n"
    "commands:\n"
    "  run CASE.json     run a case; writes OUTDIR/{resolved_case.json, <body>.pvd, <body>/*.vtu,\n"
    "                    probes.csv, log.csv, summary.json} (OUTDIR defaults to out/<case name>)\n"
    "  check CASE.json   validate a case (meshes and models are built) and print it with every\n"
    "                    default filled in; runs nothing\n"
    "  keys              print the case-file reference (every key, its default and description) as\n"
    "                    Markdown (docs/case_file_reference.md is this output)\n\n"
    "exit codes: 0 ok, 1 usage, 2 bad input, 3 solver failure (divergence), 4 internal error,\n"
    "            5 the output cannot be written (disk full, permissions), 130 / 143 interrupted\n"
    "            (SIGINT / SIGTERM: the step ends, the output is written, summary.json says \"interrupted\")\n";

const char* kRunHelp =
    "usage: lagfsi run CASE.json [-o OUTDIR] [--set key.path=value ...] [--threads N] [--quiet]\n"
    "                            [--progress auto|bar|lines|none] [--restart OUTDIR] [--stop-after-step K]\n"
    "                            [--max-nodes N]\n\n"
    "Runs a case and writes OUTDIR/{resolved_case.json, <body>.pvd, <body>/*.vtu, probes.csv, log.csv,\n"
    "summary.json}. OUTDIR (default out/<case name>) is locked while the run writes into it and must not be\n"
    "the case file's own folder.\n\n"
    "options:\n"
    "  -o, --output DIR        output folder\n"
    "  --set key.path=value    override a case value (e.g. --set analysis.dt=1e-4,\n"
    "                          --set bodies.0.mesh.size=0.01); the value is JSON or a plain string\n"
    "  --threads N             OpenMP threads for assembly (1 to 4 x the hardware threads)\n"
    "  --progress MODE         auto (default: a status line redrawn in place on a terminal, otherwise a\n"
    "                          line every 5 s and at each tenth of the run), bar, lines or none; a table of\n"
    "                          where the time went at the end\n"
    "  -q, --quiet             no progress and no warnings on stderr (errors only)\n"
    "  --restart OUTDIR        continue the run in OUTDIR from its last checkpoint: the same case file and\n"
    "                          --set options (checked), probes.csv and log.csv cut back to the checkpoint's\n"
    "                          step, the ParaView series continued; bit for bit like a run that was not\n"
    "                          stopped when the threads are the same (e.g. --threads 1)\n"
    "  --stop-after-step K     end the run after step K as if interrupted (a checkpoint is written when the\n"
    "                          case asks for them), summary.json says \"stopped\", exit code 0\n"
    "  --max-nodes N           the most nodes one mesh may have (a body's, a fluid region's particles;\n"
    "                          default 2000000): a larger one is refused as a likely mistake (a size in the\n"
    "                          wrong unit); large runs raise it (e.g. --max-nodes 5e6)\n\n"
    "Checkpoints: \"output\": {\"checkpoint\": {\"every_steps\": N, \"every_minutes\": M, \"keep\": 2}} in the\n"
    "case writes OUTDIR/checkpoint.bin every N steps and/or M minutes of wall time (atomically; keep 2 also\n"
    "keeps the one before as checkpoint.prev.bin), and when a signal ends the run. Solids, shells, fluids,\n"
    "MPM, DEM and EFG bodies and their couplings can be checkpointed.\n\n"
    "Ctrl-C (SIGINT) or SIGTERM ends the current step, writes the output (and a checkpoint) and exits with\n"
    "130 (143); a second Ctrl-C stops at once.\n"
    "exit codes: 0 ok, 1 usage, 2 bad input, 3 solver failure, 4 internal error, 5 output not written,\n"
    "            130 / 143 interrupted\n";

const char* kCheckHelp =
    "usage: lagfsi check CASE.json [--set key.path=value ...] [--max-nodes N]\n\n"
    "Validates a case (meshes and models are built, bodies checked for overlaps and output names) and\n"
    "prints it on stdout with every default filled in; runs nothing.\n\n"
    "options:\n"
    "  --set key.path=value    override a case value, as for run\n"
    "  --max-nodes N           the most nodes one mesh may have, as for run\n\n"
    "exit codes: 0 ok, 1 usage, 2 bad input, 5 stdout cannot be written\n";

const char* kKeysHelp =
    "usage: lagfsi keys\n\n"
    "Prints the case-file reference as Markdown: one section per kind of object, each a table of its keys,\n"
    "their defaults and one-line descriptions, generated from the declarations the validation uses\n"
    "(docs/case_file_reference.md is this output).\n\n"
    "exit codes: 0 ok, 1 usage, 5 stdout cannot be written\n";

/// One line on stderr: "lagfsi: error: <what>".
int usage_error(const std::string& what) {
  std::cerr << "lagfsi: error: " << what << "\n";
  return kUsage;
}

/// --threads: at most four threads per hardware thread (100 000 threads crashed the OpenMP runtime).
int max_threads() {
  const unsigned hw = std::thread::hardware_concurrency();
  return 4 * static_cast<int>(hw > 0 ? hw : 64);
}

/// The integer the whole text spells (std::stol, nothing left over), or -1.
long whole_number(const std::string& text) {
  size_t used = 0;
  long n = -1;
  try {
    n = std::stol(text, &used);
  } catch (...) {
    return -1;
  }
  return used == text.size() ? n : -1;
}

/// A node count as --max-nodes takes it: a whole number >= 1, written plainly or in exponent form (5e6); -1 for
/// anything else.
double node_count(const std::string& text) {
  double n = -1;
  size_t used = 0;
  try {
    n = std::stod(text, &used);
  } catch (...) {
    return -1;
  }
  return used == text.size() && n >= 1 && std::isfinite(n) && n == std::floor(n) ? n : -1;
}

}  // namespace

int app_main(int argc, char** argv, const char* git_commit) {
  // Under an MPI launcher every process runs the same command (mpi_run.hpp); process 0 alone prints.
  mpi_run::start();
  if (!mpi_run::writer()) {
    if (std::freopen("/dev/null", "w", stdout) == nullptr || std::freopen("/dev/null", "w", stderr) == nullptr)
      return kOutputError;
  }
  std::vector<std::string> args(argv + 1, argv + argc);
  // Every argument ends up in messages and in summary.json: it must be UTF-8.
  for (size_t i = 0; i < args.size(); ++i)
    if (!valid_utf8(args[i]))
      return usage_error("argument " + std::to_string(i + 1) + " is not UTF-8 text ('" + echo(args[i]) + "')");
  if (args.empty()) return usage_error("no command (run, check, keys; see lagfsi --help)");
  const std::string cmd = args[0];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    const std::string topic = args.size() > 1 ? args[1] : "";
    if (topic == "run")
      std::cout << kRunHelp;
    else if (topic == "check")
      std::cout << kCheckHelp;
    else if (topic == "keys")
      std::cout << kKeysHelp;
    else
      std::cout << kUsageText << "\n" << kHelp;
    return kOk;
  }
  if (cmd == "--version") {
    std::cout << "lagfsi " << LAGFSI_VERSION << " (commit " << (git_commit != nullptr ? git_commit : "unknown") << ")\n"
              << "  Eigen " << EIGEN_WORLD_VERSION << "." << EIGEN_MAJOR_VERSION << "." << EIGEN_MINOR_VERSION
              << ", SuiteSparse " << LAGFSI_SUITESPARSE_VERSION << ", VTK " << LAGFSI_VTK_VERSION << ", CGAL "
              << LAGFSI_CGAL_VERSION << "\n";
    return kOk;
  }
  if (cmd == "keys") {
    if (args.size() > 1) {
      if (args[1] == "--help" || args[1] == "-h") {
        std::cout << kKeysHelp;
        return kOk;
      }
      return usage_error("keys takes no argument (got '" + echo(args[1]) + "'; see lagfsi keys --help)");
    }
    std::cout << key_reference_markdown() << std::flush;
    return std::cout ? kOk : kOutputError;
  }
  if (cmd != "run" && cmd != "check")
    return usage_error("unknown command '" + echo(cmd) + "' (run, check, keys; see lagfsi --help)");
  // --help anywhere after the command: that command's help, whatever else the line holds.
  for (size_t i = 1; i < args.size(); ++i)
    if (args[i] == "--help" || args[i] == "-h") {
      std::cout << (cmd == "run" ? kRunHelp : kCheckHelp);
      return kOk;
    }
  const std::string see = " (see lagfsi " + cmd + " --help)";
  RunOptions opt;
  std::string progress = "auto";
  std::string restart_dir;
  for (size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    std::string v;
    auto value = [&]() -> bool {
      if (i + 1 >= args.size()) return false;
      v = args[++i];
      return true;
    };
    auto only_run = [&]() { return cmd == "run"; };
    if (a == "-o" || a == "--output") {
      if (!only_run()) return usage_error(a + " is an option of run, not of check" + see);
      if (!value()) return usage_error(a + " needs a folder" + see);
      opt.out_dir = v;
    } else if (a == "--set") {
      if (!value()) return usage_error("--set needs key.path=value" + see);
      opt.overrides.push_back(v);
    } else if (a.rfind("--set=", 0) == 0) {
      opt.overrides.push_back(a.substr(6));
    } else if (a == "--threads" || a.rfind("--threads=", 0) == 0) {
      if (a == "--threads" && !value()) return usage_error("--threads needs a number" + see);
      if (a != "--threads") v = a.substr(10);
      const long n = whole_number(v);  // -1 for "1x", "2 threads"
      if (n < 1) return usage_error("--threads needs a positive integer (got '" + echo(v) + "')");
      if (n > max_threads())
        return usage_error("--threads " + echo(v) + ": at most " + std::to_string(max_threads()) + " (4 x the " +
                           std::to_string(max_threads() / 4) + " hardware threads of this machine)");
      opt.threads = static_cast<int>(n);
    } else if (a == "--progress" || a.rfind("--progress=", 0) == 0) {
      if (a == "--progress" && !value()) return usage_error("--progress needs auto, bar, lines or none" + see);
      if (a != "--progress") v = a.substr(11);
      ProgressMode m;
      if (!parse_progress_mode(v, false, m))
        return usage_error("--progress: unknown mode '" + echo(v) + "' (auto, bar, lines or none)");
      progress = v;
    } else if (a == "--restart" || a.rfind("--restart=", 0) == 0) {
      if (!only_run()) return usage_error(a + " is an option of run, not of check" + see);
      if (a == "--restart" && !value()) return usage_error("--restart needs the output folder of the run" + see);
      if (a != "--restart") v = a.substr(10);
      if (v.empty()) return usage_error("--restart needs the output folder of the run" + see);
      restart_dir = v;
    } else if (a == "--stop-after-step" || a.rfind("--stop-after-step=", 0) == 0) {
      if (!only_run()) return usage_error(a + " is an option of run, not of check" + see);
      if (a == "--stop-after-step" && !value()) return usage_error("--stop-after-step needs a step number" + see);
      if (a != "--stop-after-step") v = a.substr(18);
      const long n = whole_number(v);
      if (n < 1) return usage_error("--stop-after-step needs a positive integer (got '" + echo(v) + "')");
      opt.stop_after_step = n;
    } else if (a == "--max-nodes" || a.rfind("--max-nodes=", 0) == 0) {
      if (a == "--max-nodes" && !value()) return usage_error("--max-nodes needs a number of nodes" + see);
      if (a != "--max-nodes") v = a.substr(12);
      const double n = node_count(v);
      if (n < 1)
        return usage_error("--max-nodes needs a positive whole number, e.g. 5000000 or 5e6 (got '" + echo(v) + "')");
      set_max_mesh_nodes(n);
    } else if (a == "--quiet" || a == "-q") {
      opt.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + echo(a) + "'" + see);
    } else if (opt.case_file.empty()) {
      opt.case_file = a;
    } else {
      return usage_error("unexpected argument '" + echo(a) + "' (one case file per run)" + see);
    }
  }
  if (opt.case_file.empty()) return usage_error(cmd + " needs a case file" + see);
  if (!restart_dir.empty()) {
    std::error_code e1, e2;
    if (!opt.out_dir.empty() && std::filesystem::weakly_canonical(std::filesystem::absolute(opt.out_dir), e1) !=
                                    std::filesystem::weakly_canonical(std::filesystem::absolute(restart_dir), e2))
      return usage_error("-o " + echo(opt.out_dir.string()) + " and --restart " + echo(restart_dir) +
                         " name two folders (--restart writes into the run's own)" + see);
    opt.out_dir = restart_dir;
    opt.restart = true;
  }
  // The same bound for OMP_NUM_THREADS (read by the OpenMP runtime when --threads is not given).
  if (const char* env = std::getenv("OMP_NUM_THREADS"); env && opt.threads == 0) {
    const long n = std::strtol(env, nullptr, 10);
    if (n > max_threads())
      return usage_error("OMP_NUM_THREADS=" + echo(env) + ": at most " + std::to_string(max_threads()) +
                         " (4 x the hardware threads of this machine)");
  }
  opt.progress = progress;
  return cmd == "run" ? run_case(opt) : check_case(opt);
}

}  // namespace lagfsi
