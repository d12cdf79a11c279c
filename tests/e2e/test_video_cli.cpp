// run --video: video.mp4 of the run (its trace replayed in sumo-gui under an Xvfb of its own,
// encoded by ffmpeg at real time speed), and a clear error before the run when a tool is missing.
#include <gtest/gtest.h>

#include <cstdlib>

#include "e2e/test_batch_support.hpp"
#include "support/cli_runner.hpp"

namespace fs = std::filesystem;
using namespace orch::test;

namespace {
// `ffprobe` of one stream property, e.g. "width", "r_frame_rate"; "duration" of the file.
std::string probe(const fs::path& video, const std::string& entry) {
  const std::string what = entry == "duration" ? "format=duration" : "stream=" + entry;
  const std::string cmd = "ffprobe -v error -select_streams v:0 -show_entries " + what +
                          " -of default=noprint_wrappers=1:nokey=1 " + shell_quote(video.string());
  FILE* pipe = ::popen(cmd.c_str(), "r");
  std::string out;
  char buf[256];
  while (pipe && std::fgets(buf, sizeof buf, pipe)) out += buf;
  if (pipe) ::pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}
}  // namespace

TEST(VideoCli, RunVideoWritesAnMp4OfTheRunAtRealTimeSpeed) {
  TempDir dir;
  const fs::path out = dir / "out";
  const auto r = run_cli({"run", std::string(ORCH_SOURCE_DIR) + "/scenarios/highway_cut_in.json", "--out", out.string(),
                          "-q", "--video", "--max-time", "4"});
  ASSERT_EQ(r.exit_code, 1) << r.output;  // --max-time: failure
  ASSERT_TRUE(fs::exists(out / "video.mp4")) << r.output;
  EXPECT_NE(r.output.find("video: file://" + fs::absolute(out / "video.mp4").string()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "video_frames")) << "the frames are removed";
  const double sim_time = read_json(out / "result.json")["sim_time"].get<double>();
  EXPECT_EQ(probe(out / "video.mp4", "r_frame_rate"), "10/1");
  EXPECT_NEAR(std::stod(probe(out / "video.mp4", "duration")), sim_time, 0.15) << "one second of video per second simulated";
  EXPECT_EQ(probe(out / "video.mp4", "width"), "1280");
  EXPECT_EQ(probe(out / "video.mp4", "height"), "720");
  EXPECT_TRUE(fs::exists(out / "report.html"));
}

TEST(VideoCli, AMissingToolIsAClearErrorBeforeTheRunStarts) {
  TempDir dir;
  const fs::path out = dir / "out";
  // No PATH: neither ffmpeg nor sumo-gui nor Xvfb can be found.
  const std::string cmd = "env -u DISPLAY PATH=/nonexistent " + shell_quote(ORCH_BINARY) + " run " +
                          shell_quote(std::string(ORCH_SOURCE_DIR) + "/scenarios/highway_cut_in.json") + " --out " +
                          shell_quote(out.string()) + " -q --video 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) output += buf;
  const int status = ::pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 2) << output;
  EXPECT_NE(output.find("--video needs ffmpeg, sumo-gui (Debian's sumo), Xvfb (no $DISPLAY)"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(out / "result.json")) << "nothing ran";
}

TEST(VideoCli, BatchVideoFilmsTheFailingRunsOnly) {
  using namespace orch::test::batch;
  TempDir in, out_root;
  const auto logical = write_quick_batch(in, {{"ok", 0.5, 5}, {"fails", 2.0, 5}});
  const fs::path out = out_root / "b";
  const auto r = run_cli({"batch", logical.string(), "--out", out.string(), "--jobs", "2", "--video"});
  ASSERT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(fs::exists(out / "runs" / run_id_of("fails") / "video.mp4")) << r.output;
  EXPECT_FALSE(fs::exists(out / "runs" / run_id_of("ok") / "video.mp4")) << r.output;
  EXPECT_TRUE(fs::exists(out / "report.html"));
}
