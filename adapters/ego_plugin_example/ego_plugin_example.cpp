// ego_plugin_example: a minimal external ego stack on SUMO's libtraci, as a system under test
// would be. It connects to `orchestrator run FILE --ego-port PORT`, perceives the ego and the
// vehicles around it through subscriptions, and each step commands one speed: the set speed,
// or less to follow the vehicle ahead in its lane (Intelligent Driver Model). It keeps its
// lane (the orchestrator lets SUMO make no lane change of its own) and switches SUMO's speed
// checks off, so that the speed is the plug-in's alone. See docs/ego-plugin.md.
//
//   ego_plugin_example --port 8813 [--host 127.0.0.1] [--speed KMH] [--range M] [--log FILE]
#include <libsumo/libtraci.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace {

namespace tc = libsumo;

struct Options {
  std::string host = "127.0.0.1";
  int port = 8813;
  double speed = 60 / 3.6;  // m/s
  double range = 150;       // m, perception radius
  std::string log;          // per-step CSV, "" none
};

// The Intelligent Driver Model's parameters: a comfortable, careful driver.
struct Idm {
  double max_accel = 1.5;       // m/s^2
  double comfortable_decel = 3.0;
  double max_decel = 8.0;       // never brakes harder
  double time_gap = 1.5;        // s
  double min_gap = 2.5;         // m at standstill
};

struct Leader {
  std::string id;
  double gap = 0;    // m, bumper to bumper
  double speed = 0;  // m/s
};

double number(const tc::TraCIResults& values, int variable) {
  const auto it = values.find(variable);
  if (it == values.end()) return 0.0;
  if (const auto* d = dynamic_cast<const tc::TraCIDouble*>(it->second.get())) return d->value;
  if (const auto* i = dynamic_cast<const tc::TraCIInt*>(it->second.get())) return i->value;
  return 0.0;
}

std::string text(const tc::TraCIResults& values, int variable) {
  const auto it = values.find(variable);
  const auto* s = it == values.end() ? nullptr : dynamic_cast<const tc::TraCIString*>(it->second.get());
  return s ? s->value : std::string{};
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "ego_plugin_example: " << arg << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--host") o.host = value();
    else if (arg == "--port") o.port = std::stoi(value());
    else if (arg == "--speed") o.speed = std::stod(value()) / 3.6;
    else if (arg == "--range") o.range = std::stod(value());
    else if (arg == "--log") o.log = value();
    else {
      std::cerr << "usage: ego_plugin_example --port PORT [--host H] [--speed KMH] [--range M] [--log FILE]\n";
      std::exit(2);
    }
  }
  return o;
}

// The nearest vehicle ahead in the ego's lane, from the context subscription around the ego.
std::optional<Leader> leader_in_lane(const tc::TraCIResults& ego, const tc::SubscriptionResults& around) {
  const std::string road = text(ego, tc::VAR_ROAD_ID);
  const int lane = static_cast<int>(number(ego, tc::VAR_LANE_INDEX));
  const double front = number(ego, tc::VAR_LANEPOSITION);
  std::optional<Leader> best;
  for (const auto& [id, values] : around) {
    if (id == "ego" || text(values, tc::VAR_ROAD_ID) != road) continue;
    if (static_cast<int>(number(values, tc::VAR_LANE_INDEX)) != lane) continue;
    const double gap = number(values, tc::VAR_LANEPOSITION) - number(values, tc::VAR_LENGTH) - front;
    if (gap < -0.5) continue;  // behind (or beside) the ego
    if (!best || gap < best->gap) best = Leader{id, gap, number(values, tc::VAR_SPEED)};
  }
  return best;
}

double idm_speed(double v, double v0, const std::optional<Leader>& leader, double dt, const Idm& p) {
  // The IDM only creeps towards a standing obstacle; a driver stops.
  if (leader && leader->speed < 0.1 && leader->gap < p.min_gap + 0.5 && v < 1.0) return 0.0;
  double accel = p.max_accel * (1 - std::pow(v / std::max(v0, 0.1), 4));
  if (leader) {
    const double dv = v - leader->speed;
    const double wanted = p.min_gap + std::max(0.0, v * p.time_gap + v * dv / (2 * std::sqrt(p.max_accel * p.comfortable_decel)));
    accel -= p.max_accel * std::pow(wanted / std::max(leader->gap, 0.1), 2);
  }
  accel = std::max(accel, -p.max_decel);
  return std::max(0.0, v + accel * dt);
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const Idm idm;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> log(nullptr, &std::fclose);
  if (!o.log.empty()) {
    log.reset(std::fopen(o.log.c_str(), "w"));
    if (!log) {
      std::cerr << "ego_plugin_example: cannot write " << o.log << "\n";
      return 2;
    }
    std::fprintf(log.get(), "time,speed,lane,leader,gap,command,hand_over,neighbours\n");
  }
  try {
    // Retries once a second while the orchestrator is still starting.
    const auto version = libtraci::Simulation::init(o.port, 60, o.host);
    std::cout << "connected: TraCI API " << version.first << ", " << version.second << "\n";
    libtraci::Simulation::setParameter("", "orch.client", "ego_plugin_example 1.0 (libtraci)");
    libtraci::Vehicle::subscribe("ego", {tc::VAR_SPEED, tc::VAR_ROAD_ID, tc::VAR_LANE_INDEX, tc::VAR_LANEPOSITION});
    libtraci::Vehicle::subscribeContext("ego", tc::CMD_GET_VEHICLE_VARIABLE, o.range,
                                       {tc::VAR_ROAD_ID, tc::VAR_LANE_INDEX, tc::VAR_LANEPOSITION, tc::VAR_LENGTH,
                                        tc::VAR_SPEED});
    // The plug-in is the driver: SUMO's own speed checks are off, the commanded speed holds.
    libtraci::Vehicle::setSpeedMode("ego", 0);
    const double dt = libtraci::Simulation::getDeltaT();
    std::string hand_over = "0";
    while (libtraci::Simulation::getMinExpectedNumber() > 0) {
      libtraci::Simulation::step();
      const tc::TraCIResults ego = libtraci::Vehicle::getSubscriptionResults("ego");
      if (ego.empty()) break;  // the ego left the simulation
      const tc::SubscriptionResults around = libtraci::Vehicle::getContextSubscriptionResults("ego");
      const double v = number(ego, tc::VAR_SPEED);
      const auto leader = leader_in_lane(ego, around);
      const double command = idm_speed(v, o.speed, leader, dt, idm);
      libtraci::Vehicle::setSpeed("ego", command);
      const std::string h = libtraci::Vehicle::getParameter("ego", "orch.hand_over");
      if (h != hand_over && !h.empty()) {
        std::cout << "t=" << libtraci::Simulation::getTime() << " hand_over " << (h == "1" ? "on" : "off") << "\n";
        hand_over = h;
      }
      if (log)
        std::fprintf(log.get(), "%.3f,%.3f,%d,%s,%.3f,%.3f,%s,%zu\n", libtraci::Simulation::getTime(), v,
                     static_cast<int>(number(ego, tc::VAR_LANE_INDEX)), leader ? leader->id.c_str() : "",
                     leader ? leader->gap : -1.0, command, hand_over.c_str(), around.size());
    }
    libtraci::Simulation::close();
    std::cout << "run over\n";
    return 0;
  } catch (const tc::TraCIException& e) {
    std::cerr << "ego_plugin_example: TraCI error: " << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "ego_plugin_example: " << e.what() << "\n";
  }
  return 1;
}
