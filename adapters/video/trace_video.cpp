#include "video/trace_video.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/process/search_path.hpp>
#include <cmath>
#include <libsumo/libtraci.h>
#include <map>
#include <set>

#include "core/checked_numeric.hpp"
#include "core/errors.hpp"
#include "core/process.hpp"
#include "results/run_files.hpp"

namespace orch::video {

namespace fs = std::filesystem;

namespace {

bool on_path(const std::string& program) { return !boost::process::search_path(program).empty(); }

// An X server of our own for sumo-gui when there is no display; ended with the video.
class OwnXvfb {
 public:
  OwnXvfb() {
    int fds[2];
    if (::pipe(fds) != 0) throw OrchError("video: cannot start Xvfb (pipe)");
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(fds[0]);
      const std::string fd = std::to_string(fds[1]);
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, STDERR_FILENO);
      ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1600x1000x24", "-nolisten", "tcp",
               static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(fds[1]);
    std::string display;
    char c;
    while (::read(fds[0], &c, 1) == 1 && c != '\n') display += c;
    ::close(fds[0]);
    if (display.empty()) throw OrchError("video: Xvfb did not start");
    ::setenv("DISPLAY", (":" + display).c_str(), 1);
  }
  ~OwnXvfb() {
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
    ::unsetenv("DISPLAY");
  }
  OwnXvfb(const OwnXvfb&) = delete;
  OwnXvfb& operator=(const OwnXvfb&) = delete;

 private:
  pid_t pid_ = -1;
};

struct Placement {
  std::string id;
  double x, y, heading, length, width;
  libsumo::TraCIColor color;
  bool ego = false;
};

// Rows of a table by time, for the frames: time -> placements.
using Frames = std::map<long long, std::vector<Placement>>;  // key: frame index

libsumo::TraCIColor color_of(const std::string& hex, bool ego) {
  if (ego) return libsumo::TraCIColor(31, 111, 209, 255);
  if (hex.size() == 6) {
    const int v = std::stoi(hex, nullptr, 16);
    return libsumo::TraCIColor((v >> 16) & 255, (v >> 8) & 255, v & 255, 255);
  }
  return libsumo::TraCIColor(214, 39, 40, 255);
}

void add_actor_frames(const RunFiles& run, double interval, Frames& frames, std::string& first_edge, std::string& ego_id) {
  const CsvTable& t = *run.trace;
  const auto c = [&](const char* name) { return *t.column(name); };
  std::map<std::string, nlohmann::json> actors;
  if (run.result.contains("actors"))
    for (const auto& a : run.result["actors"]) actors[std::to_string(a.value("actor_id", -1))] = a;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const double time = t.number(r, c("time")).value_or(0);
    const double frame = time / interval;
    if (std::abs(frame - std::round(frame)) > 1e-6) continue;  // not a frame's time
    const std::string id = t.cell(r, c("actor_id"));
    const nlohmann::json info = actors.count(id) ? actors[id] : nlohmann::json::object();
    Placement p{info.value("sumo_id", "actor" + id), *t.number(r, c("x")), *t.number(r, c("y")),
                *t.number(r, c("heading")), info.value("length", 4.5), info.value("width", 1.8),
                color_of(info.value("color", ""), info.value("ego", false)), info.value("ego", false)};
    if (p.ego) ego_id = p.id;
    if (first_edge.empty() && !t.cell(r, c("edge")).empty() && t.cell(r, c("edge"))[0] != ':') first_edge = t.cell(r, c("edge"));
    frames[orch::clamped_round<long long>(frame, 0, 1LL << 40)].push_back(std::move(p));
  }
}

void add_background_frames(const CsvTable& t, double interval, Frames& frames) {
  const auto c = [&](const char* name) { return *t.column(name); };
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const double frame = t.number(r, c("time")).value_or(0) / interval;
    if (std::abs(frame - std::round(frame)) > 1e-6) continue;
    frames[orch::clamped_round<long long>(frame, 0, 1LL << 40)].push_back({t.cell(r, c("vehicle_id")), *t.number(r, c("x")), *t.number(r, c("y")),
                                           *t.number(r, c("heading")), *t.number(r, c("length")),
                                           *t.number(r, c("width")), libsumo::TraCIColor(150, 156, 164, 255), false});
  }
}

// Screenshots of every frame into `dir` (frame_00000.png, ...); returns how many.
long long render_frames(const Frames& frames, const std::string& net, const std::string& first_edge,
                        const std::string& ego_id, double interval, const VideoOptions& o, const fs::path& dir) {
  libtraci::Simulation::start({"sumo-gui", "-n", net, "--step-length", fmt::format("{}", interval), "--start",
                               "--quit-on-end", "--window-size", fmt::format("{},{}", o.width + 40, o.height + 120),
                               "--no-warnings", "--no-step-log", "--collision.action", "none", "--delay", "0",
                               "--time-to-teleport", "-1", "--gui-settings-file", "/dev/null"});
  const std::string view = "View #0";
  libtraci::Route::add("orch_video_route", {first_edge});
  std::set<std::string> present, types;
  long long written = 0;
  bool tracking = false;
  for (const auto& [index, placements] : frames) {
    std::set<std::string> now;
    for (const auto& p : placements) {
      now.insert(p.id);
      if (!present.count(p.id)) {
        const std::string type = fmt::format("orch_video_{:.2f}x{:.2f}", p.length, p.width);
        if (types.insert(type).second) {
          libtraci::VehicleType::copy("DEFAULT_VEHTYPE", type);
          libtraci::VehicleType::setLength(type, p.length);
          libtraci::VehicleType::setWidth(type, p.width);
        }
        libtraci::Vehicle::add(p.id, "orch_video_route", type, "now");
        libtraci::Vehicle::setColor(p.id, p.color);
        libtraci::Vehicle::setSpeedMode(p.id, 0);
        present.insert(p.id);
      }
      // SUMO's angle: degrees clockwise from north; the trace's heading: radians from +x.
      libtraci::Vehicle::moveToXY(p.id, "", -1, p.x, p.y, 90.0 - p.heading * 180.0 / M_PI, 2);
    }
    for (auto it = present.begin(); it != present.end();) {
      if (now.count(*it)) {
        ++it;
        continue;
      }
      libtraci::Vehicle::remove(*it);
      it = present.erase(it);
    }
    libtraci::Simulation::step();
    if (!tracking && !ego_id.empty() && now.count(ego_id)) {
      libtraci::GUI::trackVehicle(view, ego_id);
      libtraci::GUI::setZoom(view, o.zoom);
      libtraci::GUI::setSchema(view, "real world");
      tracking = true;
    }
    libtraci::GUI::screenshot(view, (dir / fmt::format("frame_{:05d}.png", written++)).string(), o.width, o.height);
  }
  libtraci::Simulation::step();  // the last screenshot is taken at the end of a step
  libtraci::Simulation::close();
  return written;
}

}  // namespace

std::string missing_video_tools() {
  std::vector<std::string> missing;
  if (!on_path("ffmpeg")) missing.push_back("ffmpeg");
  if (!on_path("sumo-gui")) missing.push_back("sumo-gui (Debian's sumo)");
  const char* display = std::getenv("DISPLAY");
  if ((!display || !*display) && !on_path("Xvfb")) missing.push_back("Xvfb (no $DISPLAY)");
  if (missing.empty()) return "";
  return fmt::format("--video needs {} (scripts/setup.sh installs them)", fmt::join(missing, ", "));
}

fs::path write_video(const fs::path& run_dir, const VideoOptions& o) {
  if (const auto missing = missing_video_tools(); !missing.empty()) throw OrchError(missing);
  const RunFiles run = read_run_files(run_dir);
  if (!run.trace || run.trace->rows() == 0) throw OrchError(run_dir.string() + ": no trace to make a video of");
  const std::string net = run.result.contains("inputs") ? run.result["inputs"]["net"].value("path", "") : "";
  if (net.empty() || !fs::exists(net)) throw OrchError(fmt::format("video: the run's net \"{}\" is not there", net));
  Frames frames;
  std::string first_edge, ego_id;
  add_actor_frames(run, o.frame_interval_s, frames, first_edge, ego_id);
  if (run.background) add_background_frames(*run.background, o.frame_interval_s, frames);
  if (first_edge.empty()) throw OrchError(run_dir.string() + ": the trace names no edge to start the replay on");

  const fs::path frames_dir = run_dir / "video_frames";
  fs::remove_all(frames_dir);
  fs::create_directories(frames_dir);
  {
    std::optional<OwnXvfb> xvfb;
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) xvfb.emplace();
    try {
      render_frames(frames, net, first_edge, ego_id, o.frame_interval_s, o, frames_dir);
    } catch (const libsumo::TraCIException& e) {
      throw OrchError(std::string("video: sumo-gui: ") + e.what());
    }
  }
  const fs::path tmp = run_dir / "video.tmp.mp4";
  const ProcessResult ff = run_process(
      "ffmpeg", {"-y", "-loglevel", "error", "-framerate", fmt::format("{}", 1.0 / o.frame_interval_s), "-i",
                 (frames_dir / "frame_%05d.png").string(), "-c:v", "libx264", "-pix_fmt", "yuv420p", "-vf",
                 "scale=trunc(iw/2)*2:trunc(ih/2)*2", tmp.string()});
  if (ff.exit_code != 0) throw OrchError("video: ffmpeg failed: " + ff.output);
  fs::rename(tmp, run_dir / "video.mp4");
  fs::remove_all(frames_dir);
  return run_dir / "video.mp4";
}

}  // namespace orch::video
