#pragma once
// The verdict of a run (README "Outputs"): a closed set, written to result.json as text.
#include <optional>
#include <string_view>

namespace orch {

enum class Verdict { Success, Failure, Error };

constexpr const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::Success: return "success";
    case Verdict::Failure: return "failure";
    case Verdict::Error: return "error";
  }
  return "error";
}

constexpr std::optional<Verdict> parse_verdict(std::string_view text) {
  if (text == "success") return Verdict::Success;
  if (text == "failure") return Verdict::Failure;
  if (text == "error") return Verdict::Error;
  return std::nullopt;
}

}  // namespace orch
