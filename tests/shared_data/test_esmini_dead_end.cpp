// esmini's lane_change_simple.xosc drives its car to a road's dead end, leaves it stuck
// there, teleports it back and starts it again, three times. The run on SUMO keeps the
// trace honest while the car stands past the last lane (SUMO has no lane for it then: its
// lane index and positions are sentinel values that must not reach trace.csv), and both
// events on the end of the road start together (each the other's condition).
#include <gtest/gtest.h>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

TEST(EsminiDeadEnd, TheCarStuckAtTheEndIsOffEveryLaneInTheTraceAndBothEventsStart) {
  TempDir out;
  const std::string file = std::string(ORCH_SHARED_DATA_DIR) + "/esmini_examples/xosc/lane_change_simple.xosc";
  const auto r = run_cli({"run", file, "--out", out.path().string(), "-q", "--no-report", "--max-time", "40"});
  ASSERT_LE(r.exit_code, 1) << r.output;
  const Trace trace(out / "trace.csv");
  int standing_off_lane = 0;
  for (const auto& row : trace.rows()) {
    for (const char* column : {"x", "y", "lane_pos", "lat_offset", "speed"})
      EXPECT_GT(row.num(column), -1e6) << column << " at " << row.str("time");
    EXPECT_GE(row.integer("lane"), -1) << row.str("time");
    if (row.integer("lane") == -1) {
      EXPECT_EQ(row.str("edge"), "") << row.str("time");
      standing_off_lane += row.num("speed") == 0.0;  // stuck at the end: standing
    }
  }
  EXPECT_GT(standing_off_lane, 20);  // it did stand past the last lane, for more than a second
  const std::string log = slurp(out / "run.log");
  const auto start_of = [&](const std::string& event) {
    const auto at = log.find("event " + event + " startTransition");
    return at == std::string::npos ? std::string("never") : log.substr(log.rfind('\n', at) + 1, 14);
  };
  EXPECT_NE(start_of("End Of Road teleport event"), "never") << log;
  EXPECT_EQ(start_of("End Of Road speed event"), start_of("End Of Road teleport event")) << log;
}
