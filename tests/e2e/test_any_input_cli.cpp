// Any input whatsoever ends in a written result: `run` exits 0/1/2 with result.json
// (verdict error, the reason naming file and, where there is one, line and pointer);
// `validate` and `sample` report the file as bad (exit 1); nothing crashes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <regex>

#include "core/utf8.hpp"
#include "support/cli_runner.hpp"

using namespace orch::test;

namespace {

std::string cut_in() { return slurp(source_path("scenarios/highway_cut_in.json")); }

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

struct BadInput {
  std::string name;
  std::string text;
  int line;              // 0: no line to name
  std::string expected;  // in the reason
};

std::vector<BadInput> bad_inputs() {
  std::string binary;
  for (int i = 0; i < 1024; ++i) binary += static_cast<char>(i * 37 % 256);
  const std::string text = cut_in();
  return {
      {"not_json.json", "this is not JSON\n", 1, "invalid JSON"},
      {"truncated.json", text.substr(0, text.size() / 2), 0, "invalid JSON"},
      {"binary.json", binary, 1, "invalid JSON"},
      {"huge_number.json", replaced(text, "\"wp_idx\": 100}", "\"wp_idx\": 1e400}"), 14, "invalid JSON"},
      {"huge_integer.json", replaced(text, "\"wp_idx\": 100}", "\"wp_idx\": 123456789012345678901234567890}"), 14,
       "/scenario/opening_scene/ego/start_position"},
      {"nan_string.json", replaced(text, "\"wp_idx\": 100}", "\"wp_idx\": \"NaN\"}"), 14,
       "/scenario/opening_scene/ego/start_position/wp_idx"},
      {"deep.json", std::string(1 << 20, '[') + std::string(1 << 20, ']'), 1, "nested more than 256 deep"},
      {"bad_utf8.json", replaced(text, "Highway cut-in", "\xE6\x97\xA5\xE6\x9C cut-in"), 2, "UTF-8"},
  };
}

// "file:line: error: pointer: message" inside the reason or the output.
void expect_names_place(const std::string& text, const std::string& file, int line) {
  EXPECT_NE(text.find(file), std::string::npos) << text;
  if (line > 0) {
    EXPECT_NE(text.find(file + ":" + std::to_string(line) + ": error"), std::string::npos) << text;
  }
}

}  // namespace

TEST(AnyInputCli, RunWritesAnErrorResultForEveryBadInput) {
  TempDir dir;
  for (const auto& in : bad_inputs()) {
    SCOPED_TRACE(in.name);
    const auto file = dir.write(in.name, in.text);
    TempDir out;
    const auto r = run_scenario(file.string(), out);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_TRUE(orch::is_valid_utf8(r.output)) << r.output;
    const auto result = read_json(out / "result.json");
    EXPECT_EQ(result["verdict"], "error");
    const std::string reason = result["reason"].get<std::string>();
    expect_names_place(reason, file.string(), in.line);
    EXPECT_NE(reason.find(in.expected), std::string::npos) << reason;
    EXPECT_TRUE(orch::is_valid_utf8(slurp(out / "run.log")));
  }
}

TEST(AnyInputCli, ValidateReportsEveryBadInputAsInvalid) {
  TempDir dir;
  std::vector<std::string> args{"validate"};
  for (const auto& in : bad_inputs()) args.push_back(dir.write(in.name, in.text).string());
  const auto r = run_cli(args);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(orch::is_valid_utf8(r.output));
  for (const auto& in : bad_inputs()) {
    SCOPED_TRACE(in.name);
    expect_names_place(r.output, (dir / in.name).string(), in.line);
    EXPECT_NE(r.output.find((dir / in.name).string() + ": INVALID"), std::string::npos) << r.output;
  }
}

TEST(AnyInputCli, FoldersMissingAndUnreadableFilesEndInAResult) {
  TempDir dir;
  std::vector<std::pair<std::string, std::string>> cases{{dir.path().string(), "is a folder"},
                                                         {(dir / "missing.json").string(), "No such file"}};
  // Root reads any file: the permission case is only meaningful for other users.
  if (::geteuid() != 0) {
    const auto locked = dir.write("locked.json", cut_in());
    std::filesystem::permissions(locked, std::filesystem::perms::none);
    cases.emplace_back(locked.string(), "Permission denied");
  }
  for (const auto& [file, expected] : cases) {
    SCOPED_TRACE(file);
    TempDir out;
    const auto r = run_scenario(file, out);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    const std::string reason = read_json(out / "result.json")["reason"].get<std::string>();
    EXPECT_NE(reason.find(file), std::string::npos) << reason;
    EXPECT_NE(reason.find(expected), std::string::npos) << reason;
    const auto v = run_cli({"validate", file});
    EXPECT_EQ(v.exit_code, 1) << v.output;
    EXPECT_NE(v.output.find(expected), std::string::npos) << v.output;
    const auto s = run_cli({"sample", file, "--count", "1"});
    EXPECT_EQ(s.exit_code, 1) << s.output;
    EXPECT_NE(s.output.find(expected), std::string::npos) << s.output;
    const auto b = run_cli({"batch", file, "--out", (out / "batch").string()});
    EXPECT_EQ(b.exit_code, 2) << b.output;
    EXPECT_NE(b.output.find(expected), std::string::npos) << b.output;
  }
}

TEST(AnyInputCli, SampleAndBatchReportBadLogicalScenarios) {
  TempDir dir;
  for (const auto& in : bad_inputs()) {
    SCOPED_TRACE(in.name);
    const auto file = dir.write(in.name, in.text);
    // A scenario is no logical scenario: where the JSON itself is fine, the error is elsewhere.
    const int line = in.expected.front() == '/' ? 0 : in.line;
    const auto s = run_cli({"sample", file.string(), "--count", "1"});
    EXPECT_EQ(s.exit_code, 1) << s.output;
    expect_names_place(s.output, file.string(), line);
    const auto b = run_cli({"batch", file.string(), "--out", (dir / ("batch_" + in.name)).string()});
    EXPECT_EQ(b.exit_code, 2) << b.output;
    expect_names_place(b.output, file.string(), line);
    EXPECT_TRUE(orch::is_valid_utf8(s.output + b.output));
  }
}

TEST(AnyInputCli, UsageErrorsExitTwo) {
  const auto r = run_cli({"run"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(run_cli({"validate", "--no-such-flag", "x.json"}).exit_code, 2);
  EXPECT_EQ(run_cli({"--version"}).exit_code, 0);
}
