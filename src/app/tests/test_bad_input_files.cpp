// Input files and text: only regular files are read, with a size bound (a
// FIFO, /dev/zero or /dev/urandom is refused at once instead of hanging or reading gigabytes); all text is
// UTF-8 (case file, --set values, file names), checked at input with a one-line error; table rows are parsed
// strictly (';', decimal commas and malformed rows are errors naming FILE:LINE).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "bad_input.hpp"
#include "case_runner.hpp"
#include "process.hpp"

namespace {

using namespace lagfsi::testing;
using nlohmann::json;

/// The bad-input tests' static strip (tests/support/bad_input.hpp) without probes or VTK output, whose tip load
/// follows a table function from `table` (relative to the case).
json table_case(const std::string& table) {
  json j = bad_input::base_case();
  j["name"] = "files_strip";
  j.erase("probes");
  j["output"] = {{"vtk", false}};
  j["bodies"][0]["loads"][0]["function"] = {{"type", "table"}, {"file", table}};
  return j;
}

Finished run_case_in(const fs::path& dir, const fs::path& case_file, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"run", case_file.string(), "-o", (dir / "out").string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_args(args, dir);
}

void expect_one_line(const Finished& r, int code, const std::string& part) {
  EXPECT_EQ(r.code, code) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), 600u) << r.err;
}

TEST(BadInputFiles, OnlyRegularFilesAreRead) {
  const fs::path dir = fresh_dir("files_regular");
  ASSERT_EQ(::mkfifo((dir / "fifo.json").c_str(), 0644), 0);
  // A FIFO with no writer made the run wait for ever; /dev/zero and /dev/urandom were read until memory ran out.
  expect_one_line(run_case_in(dir, dir / "fifo.json"), 2, "is a FIFO, not a regular file");
  expect_one_line(run_case_in(dir, "/dev/zero"), 2, "is a character device, not a regular file");
  expect_one_line(run_case_in(dir, "/dev/urandom"), 2, "is a character device, not a regular file");
  expect_one_line(run_args({"check", "/dev/zero"}, dir), 2, "/dev/zero");
  expect_one_line(run_case_in(dir, dir), 2, "is a folder");
  // A case file of 20 MB (sparse: no disk used) is beyond the 16 MB bound.
  { std::ofstream(dir / "huge.json") << "{"; }
  fs::resize_file(dir / "huge.json", 20u << 20);
  expect_one_line(run_case_in(dir, dir / "huge.json"), 2, "more than the 16 MB");
  // The same for a table.
  for (const std::string& t : {std::string("/dev/zero"), std::string("/dev/urandom"), (dir / "fifo.json").string()}) {
    write_text(dir / "case.json", table_case(t).dump());
    expect_one_line(run_case_in(dir, dir / "case.json"), 2, "/bodies/0/loads/0/function/file");
  }
  { std::ofstream(dir / "huge.csv") << "0,0\n"; }
  fs::resize_file(dir / "huge.csv", 300u << 20);
  write_text(dir / "case.json", table_case("huge.csv").dump());
  expect_one_line(run_case_in(dir, dir / "case.json"), 2, "more than the 256 MB");
}

TEST(BadInputFiles, TextIsUtf8) {
  const fs::path dir = fresh_dir("files_utf8");
  write_text(dir / "case.json", table_case("t.csv").dump());
  write_text(dir / "t.csv", "0,0\n1,1\n");
  ASSERT_EQ(run_case_in(dir, dir / "case.json").code, 0);
  // A --set string that is not UTF-8: an uncaught JSON exception before (SIGABRT in check).
  const std::string latin1 = "caf\xE9";
  for (const std::string cmd : {"run", "check"}) {
    Finished r = run_args({cmd, (dir / "case.json").string(), "--set", "name=" + latin1}, dir);
    expect_one_line(r, 1, "not UTF-8");
    EXPECT_NE(r.err.find("caf\\xE9"), std::string::npos) << "the bad byte escaped: " << r.err;
  }
  // A case file name that is not UTF-8.
  fs::copy_file(dir / "case.json", dir / ("case_" + latin1 + ".json"));
  expect_one_line(run_args({"check", (dir / ("case_" + latin1 + ".json")).string()}, dir), 1, "not UTF-8");
  expect_one_line(run_case_in(dir, dir / ("case_" + latin1 + ".json")), 1, "not UTF-8");
  // An output folder name that is not UTF-8.
  expect_one_line(run_args({"run", (dir / "case.json").string(), "-o", (dir / latin1).string()}, dir), 1, "not UTF-8");
  // Bytes that are not UTF-8 inside the case file (in a string, in a comment): the file and line are named.
  std::string text = table_case("t.csv").dump(2);
  text.replace(text.find("files_strip"), 11, "files_" + latin1);
  write_text(dir / "latin1.json", text);
  expect_one_line(run_case_in(dir, dir / "latin1.json"), 2, "latin1.json: /: not UTF-8 text: byte");
  write_text(dir / "comment.json", "// r\xE9sum\xE9\n" + table_case("t.csv").dump(2));
  expect_one_line(run_args({"check", (dir / "comment.json").string()}, dir), 2, "(line 1) is not valid UTF-8");
  // Overlong forms and surrogates are not UTF-8 either.
  expect_one_line(run_args({"check", (dir / "case.json").string(), "--set", "name=\xC0\xAF"}, dir), 1, "not UTF-8");
  expect_one_line(run_args({"check", (dir / "case.json").string(), "--set", "name=\xED\xA0\x80"}, dir), 1, "not UTF-8");
  // Valid UTF-8 beyond ASCII is text like any other (in a description).
  Finished r =
      run_args({"check", (dir / "case.json").string(), "--set", "description=d\xC3\xA9j\xC3\xA0 \xE2\x9C\x93"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST(BadInputFiles, TableRowsAreParsedStrictly) {
  const fs::path dir = fresh_dir("files_table");
  write_text(dir / "case.json", table_case("t.csv").dump());
  auto with_table = [&](const std::string& rows) {
    write_text(dir / "t.csv", rows);
    return run_case_in(dir, dir / "case.json");
  };
  // Accepted: a header, comments, blank lines, CRLF line ends, spaces or tabs or a comma between the columns.
  EXPECT_EQ(with_table("# load\r\ntime,value\r\n0, 0\r\n\r\n0.5\t0.5\r\n1 1\r\n").code, 0);
  EXPECT_EQ(with_table("0,0\n1,+1e0\n").code, 0);
  struct Bad {
    std::string rows, part;
  };
  const std::vector<Bad> bad = {
      {"time;value\n0;0\n1;1\n", "t.csv:1: ';' is not a separator"},    // a spreadsheet's export
      {"0;0,5\n1;1,0\n", "t.csv:1: ';' is not a separator"},            // ... with decimal commas
      {"time value\n0 0,5\n1 1,0\n", "t.csv:2: expected two numbers"},  // decimal commas, spaces
      {"0 0,5\n", "decimal commas?"},
      {"0,0\n0,5,1\n1,1\n", "t.csv:2: expected two numbers (time, value), found 3"},  // read as 0.5 -> 3 columns
      {"0,0\n0.5,abc\n1,1\n", "t.csv:2: expected two numbers"},                       // a malformed row was dropped
      {"0,0\n0.5,0.5x\n1,1\n", "t.csv:2:"},
      {"0,0\n0.5\n1,1\n", "t.csv:2: expected two numbers (time, value), found 1"},
      {"time,value\nunit,unit\n0,0\n1,1\n", "t.csv:2:"},  // one header only
      {"0,0\n1,1\ntime,value\n", "t.csv:3:"},
      {"0,0\n1,nan\n", "t.csv:2:"},
      {"0,0\n1,1e999\n", "t.csv:2:"},
      {"0,0\n0,1\n", "t.csv:2: times must increase"},
      {"0,0\n", "needs at least two rows"},
  };
  for (const Bad& b : bad) {
    const Finished r = with_table(b.rows);
    expect_one_line(r, 2, b.part);
    EXPECT_NE(r.err.find("/bodies/0/loads/0/function/file"), std::string::npos) << r.err;
  }
  // A row of 100 000 characters is echoed cut.
  const Finished r = with_table("0,0\n1," + std::string(100000, '7') + "x\n");
  expect_one_line(r, 2, "t.csv:2:");
}

}  // namespace
