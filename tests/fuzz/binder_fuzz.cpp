// Fuzz target: arbitrary bytes as the three files of a nightly batch -- logical scenario,
// parameter file and scenario template, separated by lines "----8<----" -- through the
// readers, the template check, the sampler and the binder, and each bound scenario through
// the scenario loader (as `sample` and `batch` do). Bad input must end in ScenarioError or
// OrchError; anything else (another exception, a crash, a sanitizer report) is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "batch/logical_scenario.hpp"
#include "batch/parameter_file.hpp"
#include "batch/sampler.hpp"
#include "batch/sampling.hpp"
#include "batch/template_binder.hpp"
#include "core/errors.hpp"
#include "json/json_document.hpp"
#include "json/json_text.hpp"
#include "scenario_executor/loader.hpp"

namespace {

constexpr std::string_view kSeparator = "\n----8<----\n";

std::vector<std::string> split(std::string_view input) {
  std::vector<std::string> parts;
  while (parts.size() < 2) {
    const auto at = input.find(kSeparator);
    if (at == std::string_view::npos) break;
    parts.emplace_back(input.substr(0, at));
    input.remove_prefix(at + kSeparator.size());
  }
  parts.emplace_back(input);
  return parts;
}

// A bound scenario is loaded like any scenario file: it may be invalid, never a crash.
void load_bound(const std::string& text) {
  try {
    (void)orch::load_scenario(orch::JsonDocument::parse(text, "bound.json"));
  } catch (const orch::ScenarioError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto parts = split(std::string_view(reinterpret_cast<const char*>(data), size));
  if (parts.size() != 3) return 0;
  try {
    const orch::batch::LogicalScenario logical =
        orch::batch::read_logical_scenario(orch::JsonDocument::parse(parts[0], "logical.json"));
    const orch::JsonDocument tmpl = orch::JsonDocument::parse(parts[2], "template.json");
    if (orch::batch::check_template(logical, tmpl).has_errors()) return 0;
    // What `sample` does: draw values for a few seeds, bind, load.
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const auto values = orch::batch::flatten_values(nlohmann::json(orch::batch::sample_values(logical, seed)));
      load_bound(orch::json_text(orch::batch::bind_template(tmpl, values), 2));
    }
    // What `batch` does with a parameter file's sets.
    const orch::batch::ParameterFile params =
        orch::batch::read_parameter_file(orch::JsonDocument::parse(parts[1], "parameters.json"));
    for (std::size_t i = 0; i < params.sets.size() && i < 8; ++i) {
      try {
        load_bound(orch::batch::bound_scenario_text(logical, tmpl, params.sets[i]));
      } catch (const orch::ScenarioError&) {
        // A set that does not fit the logical scenario: reported, the batch goes on.
      }
    }
  } catch (const orch::OrchError&) {
    // Bad input, reported with file, line and pointer (ScenarioError is an OrchError).
  } catch (const std::exception& e) {
    std::cerr << "binder_fuzz: unexpected exception: " << e.what() << "\n";
    std::abort();
  }
  return 0;
}
