// Every text the program writes stays valid UTF-8 whatever bytes came in (file names from
// argv, the bytes nlohmann quotes in a parse error): ill-formed sequences become U+FFFD,
// never a failed write. One test per output.
#include <gtest/gtest.h>

#include <fstream>
#include <pugixml.hpp>
#include <sstream>

#include "batch/batch_report.hpp"
#include "batch/execution_trace.hpp"
#include "core/diagnostics.hpp"
#include "core/errors.hpp"
#include "core/utf8.hpp"
#include "json/json_document.hpp"
#include "json/json_text.hpp"
#include "run/run_log.hpp"
#include "run/run_result.hpp"
#include "support/cli_runner.hpp"

using namespace orch;

namespace {

const std::string kReplacement = "\xEF\xBF\xBD";
// A Japanese title cut in the middle of a character, then a stray continuation byte.
const std::string kBroken = "\xE6\x97\xA5\xE6\x9C" "'x\x80y";

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(Utf8, ValidTextIsKeptAndEachIllFormedPartBecomesOneReplacement) {
  EXPECT_TRUE(is_valid_utf8("plain \xE6\x97\xA5\xE6\x9C\xAC \xF0\x9F\x9A\x97"));
  EXPECT_EQ(valid_utf8("\xE6\x97\xA5\xE6\x9C\xAC"), "\xE6\x97\xA5\xE6\x9C\xAC");
  // A truncated 3-byte sequence is one maximal subpart: one U+FFFD, then the quote.
  EXPECT_EQ(valid_utf8(kBroken), "\xE6\x97\xA5" + kReplacement + "'x" + kReplacement + "y");
  EXPECT_FALSE(is_valid_utf8("\xC0\xAF"));          // overlong '/'
  EXPECT_EQ(valid_utf8("\xC0\xAF"), kReplacement + kReplacement);
  EXPECT_FALSE(is_valid_utf8("\xED\xA0\x80"));      // a surrogate
  EXPECT_FALSE(is_valid_utf8("\xF4\x90\x80\x80"));  // above U+10FFFF
  EXPECT_EQ(valid_utf8("ab\xF0\x9F\x9A"), "ab" + kReplacement);  // cut at the end
  EXPECT_TRUE(is_valid_utf8(valid_utf8(std::string("\xFF\xFE\x00\x80", 4))));
}

TEST(Utf8, JsonTextReplacesWhereDumpWouldThrow) {
  const nlohmann::json j{{"title", kBroken}};
  EXPECT_THROW((void)j.dump(), nlohmann::json::type_error);
  const std::string text = json_text(j, 2);
  EXPECT_TRUE(is_valid_utf8(text));
  EXPECT_NE(nlohmann::json::parse(text)["title"].get<std::string>().find(kReplacement), std::string::npos);
}

TEST(Utf8, ResultJsonIsWrittenWithBrokenBytes) {
  RunResult r;
  r.reason = "invalid scenario: " + kBroken;
  r.title = kBroken;
  r.scenario.path = "dir/" + kBroken + ".json";
  r.events.push_back({1.0, engine::EventKind::Info, kBroken});
  test::TempDir dir;
  write_result(dir.path(), r);
  const auto j = test::read_json(dir / "result.json");
  EXPECT_EQ(j["verdict"], "error");
  EXPECT_NE(j["reason"].get<std::string>().find(kReplacement), std::string::npos);
  EXPECT_NE(j["inputs"]["scenario"]["path"].get<std::string>().find(kReplacement), std::string::npos);
}

TEST(Utf8, RunLogLinesStayValid) {
  test::TempDir dir;
  {
    RunLog log(dir / "run.log", false);
    log.note("scenario " + kBroken);
    log.at(2.5, "event " + kBroken);
  }
  const std::string text = read_text(dir / "run.log");
  EXPECT_TRUE(is_valid_utf8(text)) << text;
  EXPECT_NE(text.find("scenario \xE6\x97\xA5" + kReplacement), std::string::npos) << text;
  EXPECT_NE(text.find("event"), std::string::npos);
}

TEST(Utf8, DiagnosticsPrintedOnTheTerminalStayValid) {
  Diagnostic d{Severity::Error, SourceLocation{kBroken + ".json", "/title", 3}, "bad " + kBroken};
  const std::string line = d.format();
  EXPECT_TRUE(is_valid_utf8(line)) << line;
  EXPECT_NE(line.find(":3: error: /title: bad"), std::string::npos) << line;
}

TEST(Utf8, AParseErrorQuotingBrokenBytesNamesTheLineInValidText) {
  // nlohmann rejects the ill-formed string and quotes what it last read.
  const std::string text = "{\n  \"title\": \"" + kBroken + "\"\n}\n";
  try {
    JsonDocument::parse(text, "s.json");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    const auto& d = e.diagnostics().items().at(0);
    EXPECT_EQ(d.where.line, 2);
    EXPECT_TRUE(is_valid_utf8(d.message)) << d.message;
    EXPECT_TRUE(is_valid_utf8(e.what()));
    EXPECT_NE(d.message.find("UTF-8"), std::string::npos) << d.message;
  }
}

namespace {

batch::ExecutionSummary broken_summary() {
  batch::ExecutionSummary s;
  s.run_id = "L1_P1";
  s.logical_uuid = "L1";
  s.parameter_uuid = "P1";
  s.name = "Cut-in " + kBroken;
  s.sampled_values = {{"cut_in", {{"label", kBroken}}}};
  s.verdict = "error";
  s.reason = "invalid scenario: " + kBroken;
  s.attempts = 1;
  s.run_dir = "runs/" + kBroken;
  s.file = "/tmp/executions/execution_L1_P1.json";
  return s;
}

batch::BatchReport broken_report() {
  batch::BatchReport report;
  report.total_runs = 1;
  batch::PlannedEntry e;
  e.id = "L1_P1";
  e.logical_uuid = "L1";
  e.parameter_uuid = "P1";
  e.name = "Cut-in " + kBroken;
  report.planned.push_back(e);
  report.done["L1_P1"] = broken_summary();
  report.done_in["L1_P1"] = "/tmp";
  return report;
}

}  // namespace

TEST(Utf8, ExecutionTraceIsWrittenWithBrokenBytes) {
  batch::PlannedLogical l;
  l.logical.uuid = "L1";
  l.logical.name = kBroken;
  l.logical.file = "/data/logical_L1.json";
  l.logical.template_file = "/data/" + kBroken + ".template.json";
  l.parameter_file = "/data/logical_L1_parameters.json";
  batch::PlannedRun r;
  r.logical_uuid = "L1";
  r.parameter_uuid = "P1";
  r.id = "L1_P1";
  r.name = kBroken;
  r.set.uuid = "P1";
  batch::ExecutionRecord rec;
  rec.command = {"/bin/orchestrator", "run", kBroken + ".json"};
  batch::Attempt a;
  a.verdict = "error";
  a.reason = "invalid scenario: " + kBroken;
  a.exit_code = 2;
  rec.attempts = {a};
  const std::string text = batch::execution_trace_text(r, l, rec);
  EXPECT_TRUE(is_valid_utf8(text));
  EXPECT_NE(nlohmann::json::parse(text).dump().find("invalid scenario"), std::string::npos);
}

TEST(Utf8, SummaryJsonAndJunitXmlAreWrittenWithBrokenBytes) {
  const batch::BatchReport report = broken_report();
  const std::string summary = batch::summary_json(report, "/tmp");
  EXPECT_TRUE(is_valid_utf8(summary));
  EXPECT_EQ(nlohmann::json::parse(summary)["runs"][0]["verdict"], "error");
  const std::string xml = batch::junit_xml(report);
  EXPECT_TRUE(is_valid_utf8(xml));
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(xml.c_str()));
  const auto error = doc.child("testsuites").child("testsuite").child("testcase").child("error");
  EXPECT_NE(std::string(error.attribute("message").value()).find("invalid scenario: \xE6\x97\xA5" + kReplacement),
            std::string::npos);
}
