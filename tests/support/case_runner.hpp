#pragma once
// Helpers for tests that run whole cases: run the lagfsi executable, read CSV output.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace lagfsi::testing {

namespace fs = std::filesystem;

/// Result of one run of the lagfsi executable.
struct RunResult {
  int exit_code = -1;
  std::string stderr_text;
  fs::path out_dir;
};

/// A fresh, empty folder under the build tree for one test's output.
inline fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::path(LAGFSI_BINARY_DIR) / "test_output" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// Runs `lagfsi <args>` (args already quoted as needed), capturing stderr.
inline RunResult run_lagfsi(const std::string& args, const fs::path& work_dir) {
  RunResult r;
  const fs::path err = work_dir / "stderr.txt";
  const std::string cmd = std::string("\"") + LAGFSI_EXE + "\" " + args + " 2> \"" + err.string() + "\" > \"" +
                          (work_dir / "stdout.txt").string() + "\"";
  const int status = std::system(cmd.c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::stringstream ss;
  ss << in.rdbuf();
  r.stderr_text = ss.str();
  return r;
}

/// Runs a case file from cases/ with overrides (and extra command-line options); output in a fresh folder
/// named `tag`.
inline RunResult run_case_file(const std::string& case_rel, const std::string& tag,
                               const std::vector<std::string>& sets = {}, const std::string& options = "") {
  const fs::path dir = fresh_dir(tag);
  std::string args = "run \"" + (fs::path(LAGFSI_SOURCE_DIR) / case_rel).string() + "\" -o \"" +
                     (dir / "out").string() + "\" --quiet " + options;
  for (const auto& s : sets) args += " --set '" + s + "'";
  RunResult r = run_lagfsi(args, dir);
  r.out_dir = dir / "out";
  return r;
}

/// Writes `text` as `dir`/case.json (relative paths in it start at `dir`, where the caller may have put other
/// files) and runs it with the given options; output in `dir`/out.
inline RunResult run_case_text(const fs::path& dir, const std::string& text, const std::string& options = "--quiet") {
  {
    std::ofstream o(dir / "case.json");
    o << text;
  }
  RunResult r =
      run_lagfsi("run \"" + (dir / "case.json").string() + "\" -o \"" + (dir / "out").string() + "\" " + options, dir);
  r.out_dir = dir / "out";
  return r;
}

/// A case run whole (`full`, in fresh_dir(tag + "_full")) and the same run stopped after step `stop_step`
/// (`stopped`) then restarted from its last checkpoint (`restarted`), both in fresh_dir(tag + "_part"); `options`
/// must ask for checkpoints often enough. The caller checks the exit codes and compares the outputs.
struct RestartRuns {
  RunResult full, stopped, restarted;
};
inline RestartRuns run_and_restart(const std::string& text, const std::string& options, int stop_step,
                                   const std::string& tag) {
  RestartRuns r;
  r.full = run_case_text(fresh_dir(tag + "_full"), text, options);
  const fs::path dir = fresh_dir(tag + "_part");
  r.stopped = run_case_text(dir, text, options + " --stop-after-step " + std::to_string(stop_step));
  r.restarted = run_case_text(dir, text, options + " --restart \"" + (dir / "out").string() + "\"");
  return r;
}

/// A CSV file with a header row ('#' lines skipped): every column as numbers (NaN where a cell is not one) and
/// as text (for label columns such as a series or component name).
struct Csv {
  std::vector<std::string> header;
  std::map<std::string, std::vector<double>> col;
  std::map<std::string, std::vector<std::string>> text;
  const std::vector<double>& operator[](const std::string& name) const {
    auto it = col.find(name);
    if (it == col.end()) throw std::runtime_error("no column " + name);
    return it->second;
  }
  size_t rows() const { return header.empty() ? 0 : col.at(header[0]).size(); }
};

inline Csv read_csv(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot open " + file.string());
  Csv csv;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (csv.header.empty()) {
      csv.header = cells;
      for (const auto& h : cells) csv.col[h];
      continue;
    }
    for (size_t i = 0; i < cells.size() && i < csv.header.size(); ++i) {
      double v = std::nan("");
      try {
        size_t used = 0;
        v = std::stod(cells[i], &used);
        if (cells[i].find_first_not_of(" \t\r", used) != std::string::npos) v = std::nan("");
      } catch (const std::exception&) {
      }
      csv.col[csv.header[i]].push_back(v);
      csv.text[csv.header[i]].push_back(cells[i]);
    }
  }
  return csv;
}

/// The run's summary.json.
inline nlohmann::json summary_of(const RunResult& r) {
  std::ifstream in(r.out_dir / "summary.json");
  return nlohmann::json::parse(in);
}

/// Mean of column `col` (minus column `minus`, if given) over the rows with time in [a, b].
inline double mean_between(const Csv& c, const std::string& col, double a, double b, const std::string& minus = "") {
  double s = 0;
  int n = 0;
  for (size_t i = 0; i < c.rows(); ++i)
    if (c["time"][i] >= a && c["time"][i] <= b) {
      s += c[col][i] - (minus.empty() ? 0.0 : c[minus][i]);
      ++n;
    }
  return n ? s / n : std::nan("");
}

/// probes.csv of a run that must have ended with exit code 0.
inline Csv probes_of(const RunResult& r) {
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  return read_csv(r.out_dir / "probes.csv");
}

/// Value of a column at the row whose time is closest to t (which must be within 1e-9 of a row's time).
inline double at_time(const Csv& c, const std::string& col, double t) {
  const auto& tt = c["time"];
  size_t best = 0;
  for (size_t i = 0; i < tt.size(); ++i)
    if (std::abs(tt[i] - t) < std::abs(tt[best] - t)) best = i;
  EXPECT_NEAR(tt[best], t, 1e-9);
  return c[col][best];
}

/// Tip of a cantilever elastica run (probes tip_ux, tip_uy; load factor lambda reached at t = lambda / 10)
/// against Mattiasson's table in `case_dir`/reference/mattiasson_1981_cantilever_elastica.csv: expects the
/// four rows and |w / w_ref - 1|, |u / u_ref - 1| below `tol` at each (u = -tip_ux, w = tip_uy, over L).
inline void expect_tip_matches_mattiasson(const Csv& c, const std::string& case_dir, double tol) {
  const Csv ref =
      read_csv(fs::path(LAGFSI_SOURCE_DIR) / case_dir / "reference/mattiasson_1981_cantilever_elastica.csv");
  ASSERT_EQ(ref.rows(), 4u);
  for (size_t i = 0; i < ref.rows(); ++i) {
    const double lambda = ref["lambda"][i];
    const double w = at_time(c, "tip_uy", lambda / 10.0), u = -at_time(c, "tip_ux", lambda / 10.0);
    std::printf("lambda %4.1f  w/L %.5f (%.5f)  u/L %.5f (%.5f)\n", lambda, w, ref["w_over_L"][i], u,
                ref["u_over_L"][i]);
    EXPECT_LT(std::abs(w / ref["w_over_L"][i] - 1.0), tol) << "lambda " << lambda << " w/L " << w;
    EXPECT_LT(std::abs(u / ref["u_over_L"][i] - 1.0), tol) << "lambda " << lambda << " u/L " << u;
  }
}

/// Writes a text file (for case files made by a test).
inline void write_text(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream o(file);
  o << text;
}

}  // namespace lagfsi::testing
