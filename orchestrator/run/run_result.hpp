#pragma once
// result.json: the verdict of one run and everything needed to trace it back to its inputs
// (docs/outputs.md). Written atomically at the end of every run, whatever ended it.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/verdict.hpp"
#include "criteria/criterion_result.hpp"
#include "scenario_executor_engine/engine.hpp"
#include "metrics/actor_metrics.hpp"
#include "run/ego_link.hpp"

namespace orch {

struct InputFile {
  std::string path;
  std::string sha256;
};

// A scenario actor as the run placed it: what a report needs to draw it (true size, colour).
struct ActorRecord {
  int id = 0;
  std::string sumo_id;
  std::string model_id;
  std::string description;
  std::string color;  // "rrggbb", "" = not given
  double length = 0;  // m
  double width = 0;   // m
  bool ego = false;
};

// The ego's first collision (result.json "collision"; docs/reference-driver.md).
struct CollisionFact {
  std::string with;  // "actor 1", an OpenSCENARIO entity, "vehicle <SUMO id>"
  double time = 0;
  std::optional<double> relative_speed;  // m/s, |ego speed - other speed| at that step
};

// --reference-run: the same scenario with the R157 reference driver as the ego.
struct ReferenceRunRecord {
  std::string dir = "reference";
  std::string verdict;
  std::optional<CollisionFact> reference_collision;
  std::string outcome;  // "preventable", "unavoidable", "no_collision"
  std::optional<double> min_ttc, reference_min_ttc;  // the ego's, s
  std::optional<double> min_gap, reference_min_gap;  // the ego's, m
};

// One TrafficAction of an OpenSCENARIO storyboard that ran (result.json "storyboard_traffic";
// run/openscenario_traffic.hpp counts). For a swarm, a source or an area: spawned = active_at_end +
// removed + left + not_inserted; a sink spawns none and counts what it removed.
struct TrafficActionRecord {
  std::string kind;   // "swarm", "source", "sink", "area"
  std::string name;   // the trafficName ("" none)
  std::string label;  // as run.log and traffic_actions.csv name it: the name, or "traffic<serial>"
  std::string vehicles;  // the SUMO ids of its vehicles: "traffic<serial>.N" ("" a sink)
  double started = 0;
  std::optional<double> stopped;  // a TrafficStopAction's time; none: it ran to the run's end
  int spawned = 0, removed = 0, left = 0, not_inserted = 0, active_at_end = 0;
  int removed_background = 0;  // a sink's: --traffic vehicles among `removed`
};

struct RunResult {
  Verdict verdict = Verdict::Error;
  std::string reason;
  double sim_time = 0;
  long long steps = 0;
  double step = 0;
  long long seed = 0;
  std::optional<double> max_time;
  std::string backend;
  std::string sumo_version;
  std::string title;
  std::string description;
  std::string map_id;
  InputFile scenario;
  InputFile waypoints;
  InputFile net;
  InputFile evaluation;  // the evaluation file (path empty: none)
  // Background traffic (docs/background-traffic.md): the --traffic value (or the
  // scenario's own), its route file (path empty: none), the SUMO command line the run used.
  std::string traffic = "none";
  InputFile traffic_file;
  std::vector<std::string> sumo_args;
  std::vector<engine::SceneVisit> scenes;
  std::optional<int> ending_scene;
  std::vector<engine::Event> events;
  std::vector<std::string> warnings;  // validation warnings
  std::vector<engine::Contact> collisions;     // every contact, in the order they began
  std::vector<engine::LaneChangeConflict> lane_change_conflicts;  // background traffic in a lane change's way
  std::vector<engine::HandOverRecord> hand_overs;
  std::optional<EgoLinkReport> ego_plugin;  // the external ego plug-in's connection (--ego-port)
  std::vector<ActorRecord> actors;  // empty when the run ended before its actors were known
  std::vector<metrics::ActorSummary> metrics;           // per measured actor (docs/evaluation.md)
  std::vector<criteria::CriterionResult> criteria;      // every criterion of an evaluation file
  double wall_time_s = 0;
  // Where the wall time went (docs/outputs.md): measured inside the one process, so the
  // orchestrator's own share does not depend on how fast the machine happens to be today.
  struct Timing {
    double start_s = 0;         // inputs, lane map, SUMO start, first commands
    double sumo_step_s = 0;     // inside SUMO's step (traci: with its round trip; --realtime: with its waits)
    double orchestrator_s = 0;  // the rest of every step: reading, the engine, commands, the trace
    double plugin_s = 0;        // waiting for the ego plug-in's step (--ego-port)
    double finish_s = 0;        // results, flushing, closing SUMO
    // The part of orchestrator_s each observer of the step loop took (trace, metrics, ...).
    std::vector<std::pair<std::string, double>> observers_s;
  } timing;
  long long trace_rows = 0;
  std::string ego_model = "sumo";              // what drove the ego (--ego-model)
  std::string controllers;  // OpenSCENARIO runs: "on", or "off" (--controllers off); "" not written
  std::optional<CollisionFact> collision;      // the ego's first collision
  // OpenSCENARIO runs (no metrics there): the ego's minimum gap (m) and TTC (s) to what is
  // ahead in its lane, through the reference driver's eyes.
  std::optional<double> ego_min_gap, ego_min_ttc;
  std::optional<ReferenceRunRecord> reference_run;
  // OpenSCENARIO: the storyboard's TrafficActions that started (empty: none; then null).
  std::vector<TrafficActionRecord> storyboard_traffic;
  // OpenSCENARIO 1.3 MonitorDeclarations: each monitor's value at the end (empty: none; then null).
  std::vector<std::pair<std::string, bool>> monitors;
};

std::string to_json(const RunResult& r);
void write_result(const std::filesystem::path& dir, const RunResult& r);
// 0 success, 1 failure, 2 error: a script can tell a failed test from a broken run.
int exit_code_for(const RunResult& r);

}  // namespace orch
