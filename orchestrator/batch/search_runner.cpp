#include "batch/search_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "batch/batch_report.hpp"
#include "batch/execution_trace.hpp"
#include "batch/identifiers.hpp"
#include "batch/manifest.hpp"
#include "batch/sampling.hpp"
#include "batch/search_objective.hpp"
#include "batch/search_proposal.hpp"
#include "batch/search_space.hpp"
#include "batch/template_file.hpp"
#include "core/errors.hpp"
#include "core/files.hpp"
#include "core/suggest.hpp"
#include "json/json_document.hpp"

namespace orch::batch {

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

constexpr std::size_t kBoundaryLevels = 41;
constexpr std::size_t kCriticalRuns = 5;

// One run of the search: its point and what came of it.
struct SearchRun {
  std::size_t index = 0;
  Proposal proposal;
  std::vector<double> values;
  std::string id;
  std::string verdict;
  std::optional<double> objective;
  std::optional<bool> pass;
};

struct State {
  SearchOptions o;
  fs::path out;
  SearchSpace space;
  BatchPlan plan;
  std::vector<SearchRun> runs;
  ordered_json iterations = ordered_json::array();
  bool variation = false;
};

// Options a resumed search takes from search.json unless given again.
void apply_recorded(SearchOptions& o, const nlohmann::json& rec) {
  o.input = rec.at("input").get<std::string>();
  o.objective = rec.value("objective", "");
  o.boundary = rec.value("boundary", "");
  o.method = rec.value("method", "bo");
  if (!o.budget) o.budget = rec.at("budget").get<int>();
  if (o.seed && *o.seed != rec.at("seed").get<long long>())
    throw OrchError("--resume keeps the search's --seed: give none or the same");
  o.seed = rec.at("seed").get<long long>();
  // The batch of J points per iteration depends on J: a resumed search keeps it.
  o.batch.jobs = rec.at("jobs").get<int>();
  if (!o.set_words.empty()) throw OrchError("--resume keeps the search's --set values: give none");
  o.set_words = rec.at("set").get<std::vector<std::string>>();
  if (rec.contains("max_time") && rec["max_time"].is_number()) o.max_time = rec["max_time"].get<double>();
  if (!o.resolution && rec.contains("resolution")) o.resolution = rec["resolution"].get<double>();
  if (!o.batch.timeout_s && rec.contains("timeout_s")) o.batch.timeout_s = rec["timeout_s"].get<double>();
}

ordered_json recorded_options(const State& s) {
  const SearchOptions& o = s.o;
  return {{"input", s.plan.inputs.front()}, {"objective", o.objective}, {"boundary", o.boundary}, {"method", o.method},
          {"budget", *o.budget}, {"seed", *o.seed}, {"jobs", *o.batch.jobs}, {"set", o.set_words},
          {"max_time", o.max_time ? ordered_json(*o.max_time) : ordered_json(nullptr)},
          {"timeout_s", *o.batch.timeout_s}, {"resolution", *o.resolution}};
}

ordered_json batch_options_json(const BatchOptions& o) {
  return {{"jobs", *o.jobs}, {"timeout_s", *o.timeout_s}, {"retries", *o.retries}, {"maps", o.map_dirs},
          {"catalog", o.catalog}, {"wrapper", o.wrapper}, {"ssm", o.ssm}, {"run_args", o.run_args}, {"no_fork", o.no_fork}};
}

void plan_input(State& s) {
  const fs::path input = fs::absolute(s.o.input).lexically_normal();
  if (!fs::exists(input)) throw OrchError(fmt::format("{}: no such file", input.string()));
  s.plan.inputs = {input.string()};
  std::vector<SpaceOverride> overrides;
  for (const auto& w : s.o.set_words) overrides.push_back(parse_space_override(w));
  const fs::path params = s.out / "search_parameters.json";
  if (is_variation_input(input)) {
    auto v = load_variation_logical(input);
    s.variation = true;
    s.space = variation_search_space(*v, overrides);
    s.plan.logicals.push_back(PlannedLogical{v->logical, params, {}, nullptr, v});
  } else {
    LogicalScenario logical = load_logical_scenario(input);
    s.space = logical_search_space(logical, overrides);
    auto tmpl = std::make_shared<const JsonDocument>(load_template(logical.template_file));
    if (Diagnostics d = check_templates(logical, *tmpl); d.has_errors()) throw ScenarioError(d);
    s.plan.logicals.push_back(PlannedLogical{std::move(logical), params, {}, tmpl, nullptr});
  }
  const LogicalScenario& l = s.plan.logicals.front().logical;
  for (const fs::path& f : {l.file, l.template_file})
    s.plan.input_hashes.emplace_back(f.string(), sha256_of_file(f));
}

ParameterSet make_set(const State& s, const SearchRun& r) {
  const PlannedLogical& pl = s.plan.logicals.front();
  ParameterSet set;
  set.uuid = name_based_uuid(fmt::format("{}/search/{}/{}", pl.logical.uuid, *s.o.seed, r.index));
  set.created_at = utc_timestamp();
  set.seed = *s.o.seed;  // SUMO's seed: the same for every run, so runs differ by their parameters only
  set.sampled_values = sampled_values_of(s.space, r.values, s.variation);
  set.sumo_config.step = pl.logical.sumo_config.step.value_or(0.05);
  set.sumo_config.max_time = s.o.max_time ? s.o.max_time : pl.logical.sumo_config.max_time;
  // The logical scenario's traffic and backend, as `sample` gives its sets (batch/sampling.cpp).
  set.sumo_config.traffic = pl.logical.sumo_config.traffic;
  set.sumo_config.backend = pl.logical.sumo_config.backend;
  if (s.variation) set.sumo_config.map = fs::path(pl.variation->variation.road_file).stem().string();
  set.output = nlohmann::json(output_block(pl.logical.uuid, set.uuid));
  set.where = SourceLocation{pl.logical.file.string(), "", 0};
  if (pl.variation) check_variation_set(*pl.variation, set);
  else bound_run_files(pl.logical, *pl.template_doc, set);
  return set;
}

// What came of run r: its verdict, objective and pass/fail (from result.json when it has one).
void read_outcome(const State& s, SearchRun& r) {
  const ExecutionSummary summary = read_execution_summary(execution_trace_path(s.out, r.id));
  r.verdict = summary.verdict;
  const fs::path result = s.out / "runs" / r.id / "result.json";
  if (!fs::exists(result)) return;
  const nlohmann::json j = nlohmann::json::parse(read_file(result));
  if (!s.o.objective.empty()) r.objective = objective_value(j, s.o.objective);
  if (!s.o.boundary.empty()) r.pass = criterion_passed(j, s.o.boundary);
}

// Objective values for the model: a run without one (no TTC: never closing in) counts as the
// largest value seen, the least critical.
std::vector<double> model_values(const std::vector<SearchRun>& runs) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const auto& r : runs)
    if (r.objective) worst = std::max(worst, *r.objective);
  std::vector<double> y;
  for (const auto& r : runs) y.push_back(r.objective ? *r.objective : worst);
  return y;
}

ordered_json values_json(const State& s, const std::vector<double>& values) {
  ordered_json j = ordered_json::object();
  for (std::size_t k = 0; k < values.size(); ++k) j[s.space.dims[k].key] = values[k];
  return j;
}

ordered_json run_json(const State& s, const SearchRun& r) {
  return {{"run_id", r.id}, {"run_dir", "runs/" + r.id}, {"values", values_json(s, r.values)},
          {"unit", r.proposal.point}, {"why", r.proposal.why}, {"acquisition", r.proposal.acquisition},
          {"verdict", r.verdict}, {"objective", r.objective ? ordered_json(*r.objective) : ordered_json(nullptr)},
          {"pass", r.pass ? ordered_json(*r.pass) : ordered_json(nullptr)}};
}

std::optional<std::size_t> best_run(const std::vector<SearchRun>& runs) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (runs[i].objective && (!best || *runs[i].objective < *runs[*best].objective)) best = i;
  return best;
}

std::vector<Point> points_of(const std::vector<SearchRun>& runs) {
  std::vector<Point> x;
  for (const auto& r : runs) x.push_back(r.proposal.point);
  return x;
}
std::vector<bool> passes_of(const std::vector<SearchRun>& runs) {
  std::vector<bool> p;
  for (const auto& r : runs) p.push_back(r.pass.value_or(false));
  return p;
}

// The next iteration's proposals.
std::vector<Proposal> propose(const State& s, SearchRng& rng) {
  const std::size_t budget = static_cast<std::size_t>(*s.o.budget);
  const std::size_t done = s.runs.size();
  const std::size_t dims = s.space.dims.size();
  const std::size_t jobs = static_cast<std::size_t>(*s.o.batch.jobs);
  const SnapPoint snap = [&](const Point& p) { return s.space.snap(p); };
  if (s.o.method == "grid") return grid_points(budget, dims, done, budget - done);
  if (s.o.method == "random") {
    // In boundary mode J at a time, so that search.json has the estimate after every J runs.
    const std::size_t n = s.o.boundary.empty() ? budget - done : std::min(jobs, budget - done);
    return uniform_random(n, dims, rng, snap);
  }
  if (!s.o.boundary.empty())
    return propose_boundary(dims, points_of(s.runs), passes_of(s.runs), std::min(jobs, budget - done),
                            *s.o.resolution, snap);
  const std::size_t initial = std::min(budget, initial_design_size(dims, jobs));
  if (done < initial) {  // the design's first `done` points are run: propose the rest of it
    std::vector<Proposal> design = initial_design(initial, dims, rng, snap);
    return {design.begin() + static_cast<std::ptrdiff_t>(done), design.end()};
  }
  const std::size_t count = std::min(jobs, budget - done);
  return propose_minimum(points_of(s.runs), model_values(s.runs), count, rng, snap);
}

ordered_json boundary_json(const State& s, const BoundaryEstimate& b) {
  std::string rows;
  for (bool p : b.pass) rows += p ? '1' : '0';
  return {{"keys", s.space.keys()}, {"levels", b.levels}, {"pass", rows},
          {"uncertain_fraction", b.uncertain_fraction}, {"pass_fraction", b.pass_fraction}};
}

void write_search_json(const State& s, const std::optional<BoundaryEstimate>& boundary, bool finished) {
  ordered_json dims = ordered_json::array();
  for (const auto& d : s.space.dims)
    dims.push_back({{"key", d.key}, {"unit", d.unit}, {"lower", d.lower}, {"upper", d.upper}, {"integer", d.integer},
                    {"choices", d.choices}});
  ordered_json fixed = ordered_json::object();
  for (const auto& [k, v] : s.space.fixed) fixed[k] = v;
  ordered_json j{{"search", "orchestrator search"}, {"options", recorded_options(s)}, {"finished", finished},
                 {"dimensions", dims}, {"fixed", fixed}, {"runs", s.runs.size()}, {"iterations", s.iterations}};
  if (!s.o.objective.empty()) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < s.runs.size(); ++i)
      if (s.runs[i].objective) order.push_back(i);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return *s.runs[a].objective < *s.runs[b].objective; });
    ordered_json critical = ordered_json::array();
    for (std::size_t i = 0; i < std::min(kCriticalRuns, order.size()); ++i) critical.push_back(run_json(s, s.runs[order[i]]));
    j["critical"] = critical;
  }
  if (boundary) j["boundary"] = boundary_json(s, *boundary);
  write_file_atomically(search_json_path(s.out), j.dump(1) + "\n");
}

void write_parameter_file(const State& s) {
  ParameterFile f;
  f.file = s.out / "search_parameters.json";
  f.logical_uuid = s.plan.logicals.front().logical.uuid;
  f.created_at = utc_timestamp();
  for (const auto& r : s.plan.runs) f.sets.push_back(r.set);
  write_file_atomically(f.file, to_json_text(f));
}

}  // namespace

fs::path search_json_path(const fs::path& dir) { return dir / "search.json"; }

int run_search(const SearchOptions& given) {
  State s;
  s.o = given;
  BatchOptions& b = s.o.batch;
  s.out = fs::absolute(b.out).lexically_normal();
  std::ostream& msg = *b.out_stream;
  if (b.resume) {
    if (!fs::exists(search_json_path(s.out)))
      throw OrchError(fmt::format("--resume {}: no search.json there (not a search folder)", s.out.string()));
    if (!s.o.input.empty()) throw OrchError("--resume takes the input from DIR/search.json: give no input file");
    const nlohmann::json rec = nlohmann::json::parse(read_file(search_json_path(s.out))).at("options");
    apply_recorded(s.o, rec);
  } else if (fs::exists(search_json_path(s.out)) || fs::exists(manifest_path(s.out))) {
    throw OrchError(fmt::format("{} holds a search or batch already: continue it with --resume {}, or choose another --out",
                                s.out.string(), s.out.string()));
  }
  const std::vector<std::string> methods{"bo", "random", "grid"};
  if (std::find(methods.begin(), methods.end(), s.o.method) == methods.end())
    throw OrchError(fmt::format("--method \"{}\": expected bo, random or grid{}", s.o.method, did_you_mean(s.o.method, methods)));
  if (s.o.objective.empty() && s.o.boundary.empty())
    throw OrchError("search: give --objective METRIC (minimised) and/or --boundary CRITERION");
  if (!s.o.objective.empty()) check_objective(s.o.objective);
  if (!s.o.budget || *s.o.budget < 1) throw OrchError("search: give --budget N (runs, N >= 1)");
  if (!s.o.seed) s.o.seed = 1;
  if (!s.o.resolution) s.o.resolution = 1.0 / 64;
  if (!b.jobs) b.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (!b.timeout_s) b.timeout_s = 1800;
  if (!b.retries) b.retries = 1;
  plan_input(s);

  fs::create_directories(s.out / "runs");
  fs::create_directories(s.out / "executions");
  if (b.resume) {
    const Manifest m = read_manifest(s.out);
    for (const auto& [path, sha] : s.plan.input_hashes)
      if (!m.input_sha256.count(path) || m.input_sha256.at(path) != sha)
        throw OrchError(fmt::format("{} changed since the search started: start a new search (another --out)", path));
  }
  msg << fmt::format("search: {} over {} ({}), budget {} runs, {} at a time, method {}, seed {}, into {}\n",
                     s.o.boundary.empty() ? "minimum of " + s.o.objective : "boundary of " + s.o.boundary,
                     fmt::join(s.space.keys(), ", "), s.plan.logicals.front().logical.name, *s.o.budget, *b.jobs,
                     s.o.method, *s.o.seed, s.out.string());

  SearchRng rng(static_cast<std::uint64_t>(*s.o.seed));
  std::optional<BoundaryEstimate> boundary;
  bool interrupted = false;
  while (s.runs.size() < static_cast<std::size_t>(*s.o.budget)) {
    const std::vector<Proposal> proposals = propose(s, rng);
    if (proposals.empty()) {
      msg << fmt::format("search: the boundary is resolved to cells of {:g} of each range after {} runs\n",
                         *s.o.resolution, s.runs.size());
      break;
    }
    const std::size_t first = s.runs.size();
    std::vector<std::size_t> tasks;
    for (const auto& p : proposals) {
      SearchRun r;
      r.index = s.runs.size();
      r.proposal = p;
      r.values = s.space.values(p.point);
      const ParameterSet set = make_set(s, r);
      const PlannedLogical& pl = s.plan.logicals.front();
      r.id = run_id(pl.logical.uuid, set.uuid);
      s.plan.runs.push_back(PlannedRun{r.id, pl.logical.uuid, set.uuid, pl.logical.name, 0, set});
      if (!fs::exists(execution_trace_path(s.out, r.id))) tasks.push_back(s.plan.runs.size() - 1);
      s.runs.push_back(std::move(r));
    }
    s.plan.total_runs = s.plan.runs.size();
    write_file_atomically(manifest_path(s.out), manifest_text(s.plan, batch_options_json(b)));
    write_parameter_file(s);
    if (!tasks.empty()) {
      const QueueOutcome outcome = execute_planned_runs(b, s.plan, tasks, s.out, first);
      if (outcome.interrupted) {
        interrupted = true;
        s.runs.resize(first);
        break;
      }
    }
    ordered_json points = ordered_json::array();
    for (std::size_t i = first; i < s.runs.size(); ++i) {
      read_outcome(s, s.runs[i]);
      points.push_back(run_json(s, s.runs[i]));
    }
    ordered_json it{{"iteration", s.iterations.size() + 1}, {"points", points}, {"runs_so_far", s.runs.size()}};
    if (const auto best = best_run(s.runs)) it["best_so_far"] = run_json(s, s.runs[*best]);
    if (!s.o.boundary.empty() && !s.runs.empty()) {
      // Scattered runs (random, grid) are classified by a Gaussian process, the sparse grid's by its cells.
      boundary = s.o.method == "bo" ? estimate_boundary(points_of(s.runs), passes_of(s.runs), kBoundaryLevels,
                                                        [&](const Point& p) { return s.space.snap(p); })
                                    : estimate_boundary_gp(points_of(s.runs), passes_of(s.runs), kBoundaryLevels);
      it["uncertain_fraction"] = boundary->uncertain_fraction;
      it["boundary"] = boundary_json(s, *boundary);
    }
    s.iterations.push_back(it);
    write_search_json(s, boundary, false);
    if (const auto best = best_run(s.runs); best && s.o.boundary.empty())
      msg << fmt::format("search: iteration {}: {} runs, best {} = {:g}\n", s.iterations.size(), s.runs.size(),
                         s.o.objective, *s.runs[*best].objective);
    else if (boundary)
      msg << fmt::format("search: iteration {}: {} runs, boundary uncertain over {:.1f} % of the space\n",
                         s.iterations.size(), s.runs.size(), 100 * boundary->uncertain_fraction);
  }
  write_search_json(s, boundary, !interrupted);
  BatchReport report = collect_report({s.out});
  msg << "\n" << write_reports(report, s.out);
  if (interrupted) {
    msg << fmt::format("search: interrupted: continue with `orchestrator search --resume {}`\n", s.out.string());
    return 3;
  }
  if (const auto best = best_run(s.runs); best && !s.o.objective.empty())
    msg << fmt::format("search: most critical run: {} = {:g} at {} (runs/{})\n", s.o.objective,
                       *s.runs[*best].objective, values_json(s, s.runs[*best].values).dump(), s.runs[*best].id);
  msg << fmt::format("search: {} (search.json)\n", s.out.string());
  return 0;
}

}  // namespace orch::batch
