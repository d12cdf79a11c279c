#pragma once
// video.mp4 of a run (README "Looking at results"): the run's trace replayed in sumo-gui on
// the run's own net, one screenshot per frame, following the ego, encoded by ffmpeg at real
// time speed. The replay places every traced actor (and every traced background vehicle)
// where the trace says at each frame, so the video shows what the run recorded, whichever
// backend ran it, and the run itself is not slowed by a GUI.
#include <filesystem>
#include <string>

namespace orch::video {

struct VideoOptions {
  double frame_interval_s = 0.1;  // one frame per 0.1 s of simulated time: 10 frames per second
  int width = 1280;
  int height = 720;
  double zoom = 1800;  // sumo-gui's zoom (percent): about 100 m of road from top to bottom
};

// What `run --video` needs and this machine lacks ("" when nothing): ffmpeg, sumo-gui, and
// Xvfb when there is no $DISPLAY. Checked before a run starts.
std::string missing_video_tools();

// Writes `run_dir`/video.mp4 (atomically) from the run's trace.csv, background.csv and the
// net named in result.json; starts its own Xvfb when there is no $DISPLAY. Throws OrchError
// naming what failed (no trace, sumo-gui, ffmpeg).
std::filesystem::path write_video(const std::filesystem::path& run_dir, const VideoOptions& options = {});

}  // namespace orch::video
