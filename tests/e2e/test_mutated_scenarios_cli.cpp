// Property: whatever is done to a real scenario file -- a value replaced, a key removed, a
// list item duplicated, bytes overwritten, a number made extreme but still valid (0,
// negative, x10^6, x10^-3) -- `orchestrator run` exits 0, 1 or 2, writes a parseable
// result.json whose verdict matches the exit status, and leaves no process behind.
// ORCH_PROPERTY_SEED replays a sequence; ORCH_PROPERTY_RUNS runs more (default 16).
#include <gtest/gtest.h>
#include <sys/prctl.h>
#include <sys/wait.h>

#include <random>

#include "core/utf8.hpp"
#include "support/cli_runner.hpp"
#include "support/process_tree.hpp"

using namespace orch::test;
using nlohmann::ordered_json;

namespace {

std::vector<std::filesystem::path> real_scenarios() {
  std::vector<std::filesystem::path> files;
  for (const auto& dir : {source_path("scenarios"), std::string(ORCH_SHARED_DATA_DIR) + "/roadeditor/scenarios"}) {
    if (!std::filesystem::is_directory(dir)) continue;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Every value's JSON pointer, in document order.
void pointers_of(const ordered_json& v, const std::string& at, std::vector<std::string>& out) {
  out.push_back(at);
  if (v.is_object())
    for (auto it = v.begin(); it != v.end(); ++it) pointers_of(it.value(), at + "/" + it.key(), out);
  else if (v.is_array())
    for (std::size_t i = 0; i < v.size(); ++i) pointers_of(v[i], at + "/" + std::to_string(i), out);
}

struct Mutation {
  std::string what;
  std::string text;
};

Mutation mutate(const std::string& original, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  if (pick(10) == 0) {  // bytes overwritten, anywhere (strings included: invalid UTF-8)
    std::string text = original;
    const std::size_t at = pick(text.size());
    for (std::size_t i = 0, n = 1 + pick(4); i < n && at + i < text.size(); ++i)
      text[at + i] = static_cast<char>(pick(256));
    return {"bytes at offset " + std::to_string(at), text};
  }
  ordered_json doc = ordered_json::parse(original);
  std::vector<std::string> pointers;
  pointers_of(doc, "", pointers);
  const std::string p = pointers[1 + pick(pointers.size() - 1)];
  ordered_json& v = doc[ordered_json::json_pointer(p)];
  std::string what;
  switch (pick(4)) {
    case 0: {  // a value of another type
      static const ordered_json others[] = {nullptr, true, -1, 1e300, "text", ordered_json::array(), ordered_json::object(),
                                            "NaN"};
      v = others[pick(std::size(others))];
      what = "value replaced at " + p;
      break;
    }
    case 1: {  // a key removed (of the enclosing object)
      const auto slash = p.rfind('/');
      ordered_json& parent = doc[ordered_json::json_pointer(p.substr(0, slash))];
      if (parent.is_object()) parent.erase(p.substr(slash + 1));
      what = "key removed at " + p;
      break;
    }
    case 2: {  // a list item duplicated (the nearest enclosing list)
      std::string q = p;
      while (!q.empty() && !doc[ordered_json::json_pointer(q)].is_array()) q = q.substr(0, q.rfind('/'));
      ordered_json& list = doc[ordered_json::json_pointer(q)];
      if (list.is_array() && !list.empty()) list.push_back(list[pick(list.size())]);
      what = "list item duplicated in " + q;
      break;
    }
    default: {  // extreme but valid: a number of the right type, reaching the engine
      static const double factors[] = {0.0, -1.0, 1e6, 1e-3};
      std::vector<std::string> numbers;
      for (const auto& q : pointers)
        if (doc[ordered_json::json_pointer(q)].is_number()) numbers.push_back(q);
      if (numbers.empty()) return {"unchanged", original};
      const std::string q = numbers[pick(numbers.size())];
      ordered_json& n = doc[ordered_json::json_pointer(q)];
      n = n.get<double>() * factors[pick(std::size(factors))];
      what = "number scaled at " + q;
    }
  }
  return {what, doc.dump(2)};
}

// Processes that are still our children: the orchestrator's orphans come to us (subreaper).
std::vector<pid_t> live_children() {
  while (::waitpid(-1, nullptr, WNOHANG) > 0) {
  }
  std::vector<pid_t> pids;
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = std::stoi(name);
    const auto info = proc_info(pid);
    if (info && info->ppid == ::getpid() && process_alive(pid)) pids.push_back(pid);
  }
  return pids;
}

}  // namespace

TEST(MutatedScenariosCli, EveryMutationEndsInAWrittenResult) {
  const auto files = real_scenarios();
  ASSERT_FALSE(files.empty());
  const char* seed_env = std::getenv("ORCH_PROPERTY_SEED");
  const char* runs_env = std::getenv("ORCH_PROPERTY_RUNS");
  const std::uint64_t seed = seed_env ? std::stoull(seed_env) : std::random_device{}();
  const int runs = runs_env ? std::stoi(runs_env) : 16;
  std::cout << "MutatedScenariosCli: ORCH_PROPERTY_SEED=" << seed << ", " << runs << " runs\n";
  ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 1), 0);
  std::mt19937_64 rng(seed);
  TempDir dir;
  for (int i = 0; i < runs; ++i) {
    const auto& source = files[rng() % files.size()];
    const Mutation m = mutate(slurp(source), rng);
    SCOPED_TRACE(source.filename().string() + ": " + m.what + " (ORCH_PROPERTY_SEED=" + std::to_string(seed) + ")");
    const auto file = dir.write("mutated_" + std::to_string(i) + ".json", m.text);
    TempDir out;
    // Short runs: the property is about the ending, not about the whole scenario.
    const auto r = run_scenario(file.string(), out, {"--max-time", "20"});
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == 2) << r.exit_code << "\n" << r.output;
    EXPECT_TRUE(orch::is_valid_utf8(r.output));
    ASSERT_TRUE(std::filesystem::exists(out / "result.json")) << r.output;
    const auto result = read_json(out / "result.json");
    const std::string verdict = result["verdict"].get<std::string>();
    EXPECT_EQ(r.exit_code, verdict == "success" ? 0 : verdict == "failure" ? 1 : 2) << verdict;
    EXPECT_EQ(result["reason"].get<std::string>().find("internal error"), std::string::npos) << result["reason"];
    EXPECT_TRUE(live_children().empty()) << "a process outlived the run";
  }
  ::prctl(PR_SET_CHILD_SUBREAPER, 0);
}
