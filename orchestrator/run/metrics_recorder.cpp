#include "run/metrics_recorder.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <limits>

#include "core/errors.hpp"
#include "sim/box.hpp"
#include "metrics/lane_keeping.hpp"
#include "metrics/metric_table.hpp"
#include "run/run_result.hpp"

namespace orch::metrics {

namespace {

// One metrics.csv row: the time, the actor, then every metric's columns (the table's order).
void write_row(fmt::memory_buffer& row, double time, const std::string& actor, const ActorMetrics& m) {
  row.clear();
  auto out = std::back_inserter(row);
  fmt::format_to(out, FMT_COMPILE("{:.3f},{}"), time, actor);  // compiled: no parsing per row
  for (const MetricDef& d : metric_table())
    for (const Column& c : d.columns) {
      row.push_back(',');
      if (c.cell == Cell::Partner) {
        const std::string_view partner = d.partner ? d.partner(m) : std::string_view{};
        row.append(partner.data(), partner.data() + partner.size());
      } else if (const std::optional<double> v = d.value(m)) {
        fmt::format_to(out, FMT_COMPILE("{:.3f}"), *v);
      }
    }
}

struct Measured {
  Body body;
  sim::Box box;
  bool actor = false;
};

}  // namespace

const std::string& MetricsRecorder::header() {
  static const std::string text = metrics_csv_header();
  return text;
}

MetricsRecorder::MetricsRecorder(const std::filesystem::path& csv, const LaneMap& lanes)
    : file_(csv, header()), lanes_(lanes) {
  for (int i = 0; i < static_cast<int>(lanes.lanes().size()); ++i) lane_index_[lanes.lane(i).id] = i;
}

const ActorMetrics* MetricsRecorder::current(sim::ActorId id) const {
  for (const auto& m : current_)
    if (m.actor == id) return &m;
  return nullptr;
}

std::optional<double> MetricsRecorder::departure(const sim::ActorState& a, double length, double width) const {
  const auto it = lane_index_.find(a.edge + "_" + std::to_string(a.lane));
  if (it == lane_index_.end()) return std::nullopt;
  const LaneInfo& lane = lanes_.lane(it->second);
  const LanePlace place = lanes_.place_on_lane(it->second, a.position);
  const double lane_heading = lane.shape.heading_at(place.lane_pos * lane.geometry_factor());
  return lane_departure(place.lateral, a.heading - lane_heading, length, width, lane.width);
}

void MetricsRecorder::step(const StepView& view) {
  const sim::WorldSnapshot& snap = view.run.judged();
  const double dt = last_time_ ? snap.time - *last_time_ : 0.0;
  last_time_ = snap.time;
  std::vector<Measured> bodies;
  for (const auto& a : snap.actors) {
    if (!a.present) continue;
    const auto known = view.run.body(a.id);
    if (!known) continue;
    Body b{known->label, a.position, a.heading, a.speed, known->length, known->width};
    const sim::Box box{a.position, a.heading, b.length, b.width};
    bodies.push_back({std::move(b), box, true});
  }
  for (const auto& v : snap.nearby)
    bodies.push_back({Body{v.sumo_id, v.position, v.heading, v.speed, v.length, v.width},
                      sim::Box{v.position, v.heading, v.length, v.width}, false});
  std::vector<Body> others;
  others.reserve(bodies.size());
  std::vector<TrajectoryBook::Seen> seen;
  seen.reserve(bodies.size());
  for (const auto& b : bodies) {
    others.push_back(b.body);
    seen.push_back({b.body.id, b.box});
  }
  trajectories_.record(snap.time, seen);

  current_.clear();
  fmt::memory_buffer row;
  for (const auto& a : snap.actors) {
    if (!a.present) continue;
    const auto known = view.run.body(a.id);
    if (!known || known->kind != ActorKind::Vehicle) continue;
    ActorMetrics m;
    m.time = snap.time;
    m.actor = a.id;
    m.speed = a.speed;
    const Body self{known->label, a.position, a.heading, a.speed, known->length, known->width};
    if (const Polyline* path = view.run.path_of(a.id)) {
      const Neighbours n = find_neighbours(*path, self, others);
      m.leader = n.leader;
      m.follower = n.follower;
    }
    const KinematicSample sample{snap.time, a.speed, a.heading};
    const auto before = last_sample_.find(a.id);
    const auto previous = last_kinematics_.find(a.id);
    m.kinematics = kinematics_step(before == last_sample_.end() ? nullptr : &before->second,
                                   previous == last_kinematics_.end() ? nullptr : &previous->second, sample);
    last_sample_[a.id] = sample;
    last_kinematics_[a.id] = m.kinematics;
    m.lane_departure = departure(a, self.length, self.width);

    const sim::Box own{a.position, a.heading, self.length, self.width};
    const double own_reach = std::hypot(self.length, self.width) / 2;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& b : bodies) {
      if (b.body.id == self.id) continue;
      // Centres farther apart than the best distance plus both half-diagonals cannot beat it.
      const double reach = own_reach + std::hypot(b.body.length, b.body.width) / 2;
      if ((b.body.centre - a.position).norm() - reach > best) continue;
      const double d = sim::box_distance(own, b.box);
      if (d < best) {
        best = d;
        m.min_dist_to = b.body.id;
      }
    }
    if (std::isfinite(best)) m.min_dist = best;

    write_row(row, snap.time, self.id, m);
    file_.line(std::string_view(row.data(), row.size()));
    auto& summary = summaries_[a.id];
    summary.actor = a.id;
    summary.label = self.id;
    summary.add(m, dt);
    current_.push_back(std::move(m));
  }
  // Every 200 steps the rows reach the disk even if the process dies.
  file_.end_step(200);
}

std::vector<ActorSummary> MetricsRecorder::summaries() const {
  std::vector<ActorSummary> out;
  for (const auto& [id, s] : summaries_) {
    ActorSummary whole = s;
    // The summaries over the whole run's trajectories (PET against every other body, actors and
    // background vehicles, whose path crossed this one's).
    const auto& table = metric_table();
    for (std::size_t i = 0; i < table.size(); ++i)
      if (table[i].over_run) whole.rows[i].extreme = table[i].over_run(trajectories_, s.label);
    out.push_back(std::move(whole));
  }
  return out;
}

void MetricsRecorder::finish(RunResult& result) noexcept {
  file_.flush();
  try {
    result.metrics = summaries();
  } catch (const std::exception&) {
    // Out of memory at worst: the run's verdict and files stand without the summary.
  }
}

}  // namespace orch::metrics
