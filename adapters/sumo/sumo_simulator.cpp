// SUMO adapter, compiled once per client library: ORCH_SUMO_NS is libsumo or libtraci and
// ORCH_SUMO_HEADER its header (see adapters/CMakeLists.txt). SUMO's exceptions and sentinel
// values stop here and become SimulationError with SUMO's own message. Reading goes
// through subscriptions (sumo_reader.hpp); commands are plain API calls.
#include "sumo_simulator.hpp"

#include <fmt/format.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <string_view>
#include <thread>
#include <unordered_map>

#include "core/errors.hpp"
#include "sumo_api.hpp"
#include "sumo_placement.hpp"
#include "sumo_process.hpp"
#include "sumo_reader.hpp"
#include "stderr_redirect.hpp"

namespace sumo = orch_sumo;

namespace orch {
namespace {

using sim::TrackedActor;

constexpr double kForever = 1e7;  // s; "until the end of the run" for waits and stops

// SUMO angles: degrees clockwise from north. Orchestrator headings: radians
// counter-clockwise from +x.
double to_sumo_angle(double heading) {
  double deg = 90.0 - heading * 180.0 / std::numbers::pi;
  deg = std::fmod(deg, 360.0);
  return deg < 0 ? deg + 360.0 : deg;
}

sumo::TraCIColor parse_color(const std::string& rrggbb) {
  if (rrggbb.size() != 6) return sumo::TraCIColor(255, 255, 0, 255);
  const auto byte = [&](std::size_t i) { return std::stoi(rrggbb.substr(i, 2), nullptr, 16); };
  try {
    return sumo::TraCIColor(byte(0), byte(2), byte(4), 255);
  } catch (const std::exception&) {
    return sumo::TraCIColor(255, 255, 0, 255);
  }
}

// Messages that say only that something failed; SUMO's own words are in its log instead.
bool says_nothing(std::string_view message) {
  return message.empty() || message == "Process Error" || message.find("tcpip::Socket") != std::string_view::npos ||
         message == "Not connected." || message.find("connection closed") != std::string_view::npos;
}

class SumoSimulator final : public Simulator {
 public:
  explicit SumoSimulator(SumoBackendOptions options) : options_(std::move(options)) {}
  ~SumoSimulator() override { close(); }
  SumoSimulator(const SumoSimulator&) = delete;
  SumoSimulator& operator=(const SumoSimulator&) = delete;

  void start(const SimulatorConfig& config) override {
    log_file_ = config.log_file;
    const std::vector<std::string> args = sumo_arguments(config);
#ifdef LIBTRACI
    start_traci(args);
#else
    start_libsumo(args);
#endif
    guard("subscribing to the simulation", [&] { reader_.start(); });
  }

  void apply(const std::vector<sim::Command>& commands) override {
    for (const auto& c : commands) std::visit([this](const auto& cmd) { execute(cmd); }, c);
  }

  void advance() override {
    guard("simulation step", [this] {
      sumo::Simulation::step();
      reader_.after_step();
      for (const auto& [id, speed] : pending_max_speed_) sumo::Vehicle::setMaxSpeed(id, speed);
      pending_max_speed_.clear();
    });
  }

  sim::WorldSnapshot read(const std::vector<TrackedActor>& actors) override {
    sim::WorldSnapshot snap;
    guard("reading the simulation", [&] {
      snap = reader_.read(actors);
      if (step_ <= 0) step_ = sumo::Simulation::getDeltaT();
    });
    placements_.placed_accelerations(actors, snap, step_);
    return snap;
  }

  double time() override { return reader_.time(); }

  [[nodiscard]] std::string backend() const override { return ORCH_SUMO_BACKEND; }

  std::string version() override {
    std::string v;
    guard("reading SUMO's version", [&] { v = sumo::Simulation::getVersion().second; });
    return v;
  }

  void close() override {
    if (started_) {
      started_ = false;
      try {
        // After a lost connection there is nobody to say goodbye to.
        if (!broken_) sumo::Simulation::close();
      } catch (const std::exception&) {
        // Closing after SUMO already failed: nothing left to release.
      }
    }
#ifdef LIBTRACI
    // SUMO quits after the close command; give it a moment to finish its logs.
    process_.stop(broken_ ? 0.0 : 5.0);
#endif
    silencer_.release();
  }

 private:
#ifndef LIBTRACI
  void start_libsumo(const std::vector<std::string>& args) {
    std::vector<std::string> cmd{"sumo"};
    cmd.insert(cmd.end(), args.begin(), args.end());
    StderrRedirect printed(StderrRedirect::Target::Capture);  // a broken net: stderr only
    try {
      sumo::Simulation::start(cmd);
    } catch (const std::exception& e) {
      throw SimulationError("SUMO could not start: " + sumo_message(e.what(), printed.release()));
    }
    printed.release();
    started_ = true;
    silencer_.engage(StderrRedirect::Target::Silence);
  }
#else
  void start_traci(const std::vector<std::string>& args) {
    // Writing to a SUMO that died must fail with EPIPE, not kill the orchestrator.
    ::signal(SIGPIPE, SIG_IGN);
    if (!options_.connect.empty()) {
      const auto colon = options_.connect.rfind(':');
      int port = -1;
      try {
        port = std::stoi(options_.connect.substr(colon + 1));
      } catch (const std::exception&) {
      }
      if (colon == std::string::npos || colon == 0 || port <= 0 || port > 65535)
        throw SimulationError(fmt::format("--connect {}: expected HOST:PORT", options_.connect));
      connect(options_.connect.substr(0, colon), port);
      // The running SUMO loads this run's net, traffic and settings, so that a run is the
      // same whoever started SUMO.
      guard("loading the scenario's simulation into the running SUMO", [&] { sumo::Simulation::load(args); });
      return;
    }
    const int port = free_loopback_port();
    std::vector<std::string> cmd{options_.gui ? "sumo-gui" : "sumo"};
    cmd.insert(cmd.end(), args.begin(), args.end());
    cmd.insert(cmd.end(), {"--remote-port", std::to_string(port)});
    if (options_.gui) cmd.insert(cmd.end(), {"--start", "true", "--quit-on-end", "true"});
    process_.spawn(cmd);
    connect("127.0.0.1", port);
  }

  // libtraci retries once a second and prints each try. Here a SUMO that exits at once (a
  // broken net) is noticed at once, and the connection is made as soon as SUMO listens.
  void connect(const std::string& host, int port) {
    const auto before = open_socket_fds();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(options_.startup_timeout);
    for (int attempt = 0;; ++attempt) {
      if (process_.started() && !process_.running()) {
        const std::string why = sumo_message("", "");
        throw SimulationError(fmt::format("SUMO {} before accepting the TraCI connection{}{}", process_.describe_exit(),
                                          why.empty() ? "" : ": ", why));
      }
      std::string failure;
      // Knock only once SUMO listens (when it runs on this machine): an early connect to a
      // closed port could be given that port as its own and talk to itself.
      const bool local = process_.started() || host == "127.0.0.1" || host == "localhost";
      if (!local || port_is_listening(port)) {
        try {
          // A fresh label per attempt: a failed attempt may leave its connection registered.
          sumo::Simulation::init(port, 0, host, fmt::format("orch{}", attempt));
          break;
        } catch (const std::exception& e) {
          failure = e.what();
        }
      }
      if (std::chrono::steady_clock::now() > deadline) {
        process_.stop(0.0);
        throw SimulationError(fmt::format("SUMO did not accept a TraCI connection on {}:{} within {:g} s{}{}", host,
                                          port, options_.startup_timeout, failure.empty() ? "" : ": ", failure));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    started_ = true;
    if (options_.reply_timeout > 0) set_socket_deadline(before, port, options_.reply_timeout);
  }
#endif

  // SUMO's own words for a failure: the exception's message when it says something, else
  // the errors SUMO printed (libsumo) or wrote to its log.
  std::string sumo_message(const std::string& raw, const std::string& printed) const {
    std::string errors = sumo_errors_in(printed);
    if (errors.empty() && !log_file_.empty()) errors = sumo_errors_in_file(log_file_);
    // One line: SUMO continues its messages on indented lines.
    std::string message;
    for (const char c : raw) {
      if (c == '\n') {
        message += ' ';
      } else if (c != ' ' || message.empty() || message.back() != ' ') {
        message += c;
      }
    }
    if (says_nothing(message)) return errors.empty() ? message : errors;
    if (!errors.empty() && errors.find(message) == std::string::npos && message.find(errors) == std::string::npos)
      return message + " (SUMO: " + errors + ")";
    return message;
  }

  // Every SUMO call goes through here: its exceptions become SimulationError. On the traci
  // backend a lost or silent connection is told apart from a SUMO error.
  template <typename F>
  void guard(const char* what, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      f();
    } catch (const sumo::TraCIException& e) {
      throw SimulationError(fmt::format("SUMO error while {}: {}", what, sumo_message(e.what(), "")));
    } catch (const SimulationError&) {
      throw;
    } catch (const std::exception& e) {
      // FatalTraCIError, tcpip::SocketException: the connection is gone or SUMO is silent.
      broken_ = true;
      const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      throw SimulationError(connection_failure(what, e.what(), waited));
    }
  }

  std::string connection_failure(const char* what, const std::string& message, double waited) {
#ifdef LIBTRACI
    const bool timed_out = options_.reply_timeout > 0 && waited >= options_.reply_timeout * 0.9;
    if (process_.started()) {
      // A SUMO that quits on an error closes the connection first and exits a moment
      // later, its log complete.
      if (process_.wait_exit(timed_out ? 0.0 : 2.0)) {
        const std::string why = sumo_message("", "");
        return fmt::format("SUMO {} during {}{}{}", process_.describe_exit(), what, why.empty() ? "" : ": ", why);
      }
      if (timed_out) {
        process_.stop(0.0);
        return fmt::format("SUMO did not answer within {:g} s during {} (hung; it was stopped)", options_.reply_timeout,
                           what);
      }
    } else if (timed_out) {
      return fmt::format("SUMO at {} did not answer within {:g} s during {}", options_.connect, options_.reply_timeout,
                         what);
    }
#else
    (void)waited;
#endif
    return fmt::format("SUMO failed while {}: {}", what, sumo_message(message, ""));
  }

  std::string make_type(const std::string& base, const std::string& sumo_id, const ModelInfo& m,
                        const std::string& color) {
    const std::string type = "orch." + sumo_id;
    sumo::VehicleType::copy(base, type);
    sumo::VehicleType::setLength(type, m.length);
    sumo::VehicleType::setWidth(type, m.width);
    sumo::VehicleType::setHeight(type, m.height);
    if (!color.empty()) sumo::VehicleType::setColor(type, parse_color(color));
    return type;
  }

  void execute(const sim::SpawnVehicle& c) {
    if (c.traffic) reader_.expect_traffic(c.actor.sumo_id, c.model.length, c.model.width);
    else reader_.expect(c.actor);
    guard("inserting a vehicle", [&] {
      const std::string type = make_type("DEFAULT_VEHTYPE", c.actor.sumo_id, c.model, c.color);
      sumo::VehicleType::setVehicleClass(type, c.model.vclass);
      sumo::VehicleType::setShapeClass(type, c.model.gui_shape);
      // Deterministic driver: no dawdling, no speed deviation.
      sumo::VehicleType::setImperfection(type, 0.0);
      // Speed factor 1 for scripted actors too: SUMO sizes every lane's leader and follower
      // search by the largest speed factor of any type, so a large one would make each
      // background car look kilometres around itself (twice the run time in dense traffic).
      sumo::VehicleType::setSpeedFactor(type, 1.0);
      sumo::VehicleType::setSpeedDeviation(type, 0.0);
      if (c.scripted) sumo::VehicleType::setMaxSpeed(type, 300.0 / 3.6 * 2);
      const std::string route = "orch.route." + c.actor.sumo_id;
      sumo::Route::add(route, c.route);
      const std::string lane_id = c.edge + "_" + std::to_string(c.lane);
      const double lane_length = sumo::Lane::getLength(lane_id);
      const double front = std::clamp(c.lane_pos + c.actor.length / 2, 0.0, lane_length);
      // Never a negative or non-finite departSpeed (SUMO refuses it): an entity standing,
      // reversing or without a speed yet departs standing; a scripted one gets its exact
      // speed with its first pose (speed mode 0).
      const double speed = std::isfinite(c.speed) ? std::max(c.speed, 0.0) : 0.0;
      const double lane_max = sumo::Lane::getMaxSpeed(lane_id);
      // SUMO refuses to insert a vehicle faster than the lane allows: a scripted actor departs
      // at the limit (its first pose sets its speed), a driven one at the storyboard's speed.
      const double depart_speed = c.scripted ? std::min(speed, lane_max) : speed;
      if (!c.scripted) allow_driven_speeds(type, c, lane_id, depart_speed);
      sumo::Vehicle::add(c.actor.sumo_id, route, type, "now", std::to_string(c.lane), fmt::format("{:.3f}", front),
                         fmt::format("{:.3f}", depart_speed));
      if (c.scripted) {
        placements_.spawned(c.actor.sumo_id, c.route, c.model.vclass);
        // Placed by the orchestrator every step: SUMO must neither slow nor steer it.
        sumo::Vehicle::setSpeedMode(c.actor.sumo_id, 0);
        sumo::Vehicle::setLaneChangeMode(c.actor.sumo_id, 0);
      } else {
        // The built-in ego keeps the lane of its route and drives at the route's speed;
        // traffic changes lanes as SUMO's background does.
        if (!c.traffic) sumo::Vehicle::setLaneChangeMode(c.actor.sumo_id, 0);
        // SUMO checks the departure speed against the vehicle's maximum speed again when it
        // inserts it (the next step): a desired speed below the departure speed waits for that.
        if (c.max_speed > 0 && c.max_speed < depart_speed) pending_max_speed_[c.actor.sumo_id] = c.max_speed;
        else if (c.max_speed > 0) sumo::Vehicle::setMaxSpeed(c.actor.sumo_id, c.max_speed);
        if (c.keep_lateral) sumo::VehicleType::setLateralAlignment(type, "arbitrary");
      }
    });
  }

  // A vehicle SUMO drives departs at its given speed (the storyboard's) even above the lane's
  // limit: SUMO caps a vehicle's speed at limit x speed factor and refuses a departure above
  // it ("Departure speed ... is too high for the departure edge"), so such a vehicle's type
  // gets the speed factor (and maximum speed) that allows its departure speed; it then keeps
  // at most that speed where the limit is the same. Within the limit nothing changes (speed
  // factor 1, see make_type's caller on speed factors).
  void allow_driven_speeds(const std::string& type, const sim::SpawnVehicle& c, const std::string& lane_id,
                           double depart_speed) {
    // SUMO checks the edge by its first lane, then the departure lane.
    const double limit = std::min(sumo::Lane::getMaxSpeed(lane_id), sumo::Lane::getMaxSpeed(c.edge + "_0"));
    if (limit > 0 && depart_speed > limit) sumo::VehicleType::setSpeedFactor(type, depart_speed / limit * 1.001);
    if (depart_speed > sumo::VehicleType::getMaxSpeed(type)) sumo::VehicleType::setMaxSpeed(type, depart_speed * 1.001);
  }

  void execute(const sim::SpawnPerson& c) {
    reader_.expect(c.actor);
    guard("inserting a pedestrian", [&] {
      const std::string type = make_type("DEFAULT_PEDTYPE", c.actor.sumo_id, c.model, c.color);
      sumo::Person::add(c.actor.sumo_id, c.edge, c.lane_pos, libsumo::DEPARTFLAG_NOW, type);
      // Stands until placed elsewhere; poses come from the orchestrator every step.
      sumo::Person::appendWaitingStage(c.actor.sumo_id, kForever, "scenario actor");
    });
  }

  void execute(const sim::SetPose& c) {
    guard("placing an actor", [&] {
      const double angle = to_sumo_angle(c.heading);
      if (c.kind == ActorKind::Pedestrian) {
        sumo::Person::moveToXY(c.sumo_id, c.edge, c.position.x(), c.position.y(), angle, 2);
        return;
      }
      const Vec2 front = c.position + (c.length / 2) * Vec2(std::cos(c.heading), std::sin(c.heading));
      if (!c.scripted) {
        placements_.forget(c.sumo_id);
        sumo_placing::move_to_xy(c.sumo_id, c.edge, c.lane, front, angle, 2);
        return;
      }
      // Free placement (2), or along the route when that gives the same (sumo_placement.hpp).
      sumo_placing::move_to_xy(c.sumo_id, c.edge, c.lane, front, angle,
                 placements_.keep_route(c.sumo_id, c.edge, c.lane, front, c.heading));
      // Without an explicit speed SUMO derives one from the lane positions, which jump when
      // the vehicle crosses into another lane of a curved edge: followers would see a
      // phantom brake. The scenario's speed is exact. SUMO keeps a speed and signals set
      // over TraCI until they are set again, so each is sent when it changes: on the traci
      // backend every call is a round trip to SUMO.
      Sent& sent = sent_[c.sumo_id];
      if (!sent.speed || *sent.speed != c.speed) {
        sumo::Vehicle::setSpeed(c.sumo_id, c.speed);
        sent.speed = c.speed;
      }
      if (sent.signals != c.signals) {
        sumo::Vehicle::setSignals(c.sumo_id, c.signals);
        sent.signals = c.signals;
      }
    });
  }

  void execute(const sim::SetSignals& c) {
    guard("setting signals", [&] {
      sumo::Vehicle::setSignals(c.sumo_id, c.signals);
      sent_[c.sumo_id].signals = c.signals;
    });
  }

  void execute(const sim::SetMaxSpeed& c) {
    if (const auto pending = pending_max_speed_.find(c.sumo_id); pending != pending_max_speed_.end()) {
      pending->second = c.speed;  // not inserted yet: set after the step (execute(SpawnVehicle))
      return;
    }
    guard("setting a speed", [&] { sumo::Vehicle::setMaxSpeed(c.sumo_id, c.speed); });
  }

  void execute(const sim::SetStop& c) {
    guard("setting the ego's stop", [&] {
      const double lane_length = sumo::Lane::getLength(c.edge + "_" + std::to_string(c.lane));
      const double front = std::clamp(c.lane_pos + c.length / 2, 0.0, lane_length);
      sumo::Vehicle::setStop(c.sumo_id, c.edge, front, c.lane, kForever);
    });
  }

  void execute(const sim::DriveSpeed& c) {
    guard("driving the ego", [&] {
      Sent& sent = sent_[c.sumo_id];
      if (!sent.speed_mode_off) {
        sumo::Vehicle::setSpeedMode(c.sumo_id, 0);
        sent.speed_mode_off = true;
      }
      sumo::Vehicle::setSpeed(c.sumo_id, c.speed);
    });
  }

  void execute(const sim::SetParameter& c) {
    guard("setting a parameter", [&] { sumo::Vehicle::setParameter(c.sumo_id, c.key, c.value); });
  }

  void execute(const sim::RemoveActor& c) {
    guard("removing an actor", [&] {
      reader_.forget(c.sumo_id);
      if (c.kind == ActorKind::Pedestrian) sumo::Person::remove(c.sumo_id);
      else sumo::Vehicle::remove(c.sumo_id);
      sent_.erase(c.sumo_id);
      pending_max_speed_.erase(c.sumo_id);
      placements_.forget(c.sumo_id);
    });
  }

  void execute(const sim::ReleaseActor& c) {
    guard("handing an actor to SUMO", [&] {
      sumo::Vehicle::setSpeedMode(c.sumo_id, 31);  // SUMO's default: safe speeds, brakes for leaders
      sumo::Vehicle::setSpeed(c.sumo_id, -1);      // its own speed from now on
      if (c.max_speed > 0) sumo::Vehicle::setMaxSpeed(c.sumo_id, c.max_speed);
      sent_.erase(c.sumo_id);
      placements_.forget(c.sumo_id);
    });
  }

  void execute(const sim::SetRoute& c) {
    guard("giving a vehicle its route", [&] {
      // SUMO wants the new route to start at the vehicle's current route edge.
      const auto route = sumo::Vehicle::getRoute(c.sumo_id);
      const int at = sumo::Vehicle::getRouteIndex(c.sumo_id);
      if (at < 0 || at >= static_cast<int>(route.size())) return;
      const auto from = std::find(c.edges.begin(), c.edges.end(), route[static_cast<std::size_t>(at)]);
      if (from != c.edges.end()) sumo::Vehicle::setRoute(c.sumo_id, std::vector<std::string>(from, c.edges.end()));
    });
  }

  void execute(const sim::SetTrafficLight& c) {
    guard("setting a traffic light", [&] {
      std::string state = sumo::TrafficLight::getRedYellowGreenState(c.tls_id);
      for (std::size_t i = 0; i < c.links.size() && i < state.size(); ++i)
        if (c.links[i] != '-') state[i] = c.links[i];
      sumo::TrafficLight::setRedYellowGreenState(c.tls_id, state);
    });
  }

  SumoBackendOptions options_;
  std::string log_file_;
  bool started_ = false;
  bool broken_ = false;  // the connection to SUMO is lost: no more calls
  sumo_reading::WorldReader reader_;
  StderrRedirect silencer_;
#ifdef LIBTRACI
  SumoProcess process_;
#endif
  struct Sent {  // what a scripted vehicle was last given
    std::optional<double> speed;
    int signals = 0;  // SUMO's own until set
    bool speed_mode_off = false;  // DriveSpeed switched SUMO's own speed checks off
  };
  std::unordered_map<std::string, Sent> sent_;
  double step_ = 0;  // SUMO's step length (s), read once
  sumo_placing::Placements placements_;  // which scripted vehicles SUMO may match along their route
  // Driven vehicles added this step whose desired speed is below their departure speed: set
  // after the step that inserts them (execute(SpawnVehicle)).
  std::unordered_map<std::string, double> pending_max_speed_;
};

}  // namespace

ORCH_SUMO_CONCAT(contexts_, ORCH_SUMO_NS)::SharedContexts& ORCH_SUMO_CONCAT(contexts_, ORCH_SUMO_NS)::shared_contexts() {
  static SharedContexts table;
  return table;
}

std::unique_ptr<Simulator> ORCH_SUMO_FACTORY(const SumoBackendOptions& options) {
  return std::make_unique<SumoSimulator>(options);
}

}  // namespace orch
