// Benchmark baseline (scripts/bench/split.py): SUMO with the scenario's vehicles present and
// nothing of the orchestrator. The same SUMO command line as an orchestrator run (its
// result.json's sumo_args), the run's actors inserted as the orchestrator inserts them
// (their own type: length, width, speed factor 1, no dawdling; speed mode and lane-change
// mode 0) and moved every step with moveToXY (and setSpeed when it changes) to the poses of
// the run's trace.csv: SUMO simulates the same vehicles at the same places, with no engine,
// no trace, no subscriptions. The ego is replayed too (the orchestrator lets SUMO drive it).
//
//   actors_baseline RESULT_JSON TRACE_CSV STEPS SUMO_LOG
#include <libsumo/libsumo.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Pose {
  double x = 0, y = 0, heading = 0, speed = 0, lane_pos = 0;
  std::string edge;
  int lane = 0;
};

struct Actor {
  std::string sumo_id;
  double length = 0, width = 0;
  std::map<long, Pose> poses;  // by step index (time / step - 1)
  bool inserted = false;
  double sent_speed = -1;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: actors_baseline RESULT_JSON TRACE_CSV STEPS SUMO_LOG\n";
    return 2;
  }
  const nlohmann::json result = nlohmann::json::parse(std::ifstream(argv[1]));
  std::vector<std::string> args = {"sumo"};
  for (const auto& a : result.at("sumo_args")) args.push_back(a.get<std::string>());
  const auto log = std::find(args.begin(), args.end(), "--log");
  if (log != args.end() && log + 1 != args.end()) *(log + 1) = argv[4];
  const double step = std::stod(*(std::find(args.begin(), args.end(), "--step-length") + 1));
  const long steps = std::stol(argv[3]);

  std::map<int, Actor> actors;
  for (const auto& a : result.at("actors"))
    actors[a.at("actor_id").get<int>()] = {a.at("sumo_id"), a.at("length"), a.at("width"), {}};
  std::ifstream trace(argv[2]);
  std::string line;
  std::getline(trace, line);
  std::map<std::string, std::size_t> column;
  for (const auto& name : split(line)) column.emplace(name, column.size());
  while (std::getline(trace, line)) {
    const auto c = split(line);
    const auto actor = actors.find(std::stoi(c.at(column.at("actor_id"))));
    if (actor == actors.end()) continue;
    Pose p{std::stod(c.at(column.at("x"))), std::stod(c.at(column.at("y"))), std::stod(c.at(column.at("heading"))),
           std::stod(c.at(column.at("speed"))), std::stod(c.at(column.at("lane_pos"))), c.at(column.at("edge")),
           std::stoi(c.at(column.at("lane")))};
    actor->second.poses[std::lround(std::stod(c.at(0)) / step) - 1] = p;
  }

  libsumo::Simulation::start(args);
  for (long k = 0; k < steps; ++k) {
    for (auto& [id, a] : actors) {
      const auto it = a.poses.find(k);
      if (it == a.poses.end() || it->second.edge.empty()) continue;
      const Pose& p = it->second;
      if (!a.inserted) {
        const std::string type = "orch." + a.sumo_id, route = "orch.route." + a.sumo_id;
        libsumo::VehicleType::copy("DEFAULT_VEHTYPE", type);
        libsumo::VehicleType::setLength(type, a.length);
        libsumo::VehicleType::setWidth(type, a.width);
        libsumo::VehicleType::setImperfection(type, 0.0);
        libsumo::VehicleType::setSpeedFactor(type, 1.0);
        libsumo::VehicleType::setSpeedDeviation(type, 0.0);
        libsumo::VehicleType::setMaxSpeed(type, 300.0 / 3.6 * 2);
        libsumo::Route::add(route, {p.edge});
        const std::string lane = p.edge + "_" + std::to_string(p.lane);
        const double front = std::clamp(p.lane_pos + a.length / 2, 0.0, libsumo::Lane::getLength(lane));
        const double speed = std::min(p.speed, libsumo::Lane::getMaxSpeed(lane));
        libsumo::Vehicle::add(a.sumo_id, route, type, "now", std::to_string(p.lane), std::to_string(front),
                              std::to_string(speed));
        libsumo::Vehicle::setSpeedMode(a.sumo_id, 0);
        libsumo::Vehicle::setLaneChangeMode(a.sumo_id, 0);
        a.inserted = true;
        continue;
      }
      const double fx = p.x + a.length / 2 * std::cos(p.heading), fy = p.y + a.length / 2 * std::sin(p.heading);
      libsumo::Vehicle::moveToXY(a.sumo_id, p.edge, p.lane, fx, fy, 90.0 - p.heading * 180.0 / std::numbers::pi, 2);
      if (p.speed != a.sent_speed) {
        libsumo::Vehicle::setSpeed(a.sumo_id, p.speed);
        a.sent_speed = p.speed;
      }
    }
    libsumo::Simulation::step();
  }
  std::cout << "actors_baseline: " << steps << " steps, " << libsumo::Vehicle::getIDCount() << " vehicles at the end\n";
  libsumo::Simulation::close();
  return 0;
}
