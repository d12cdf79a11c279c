#pragma once
// "Did you mean" for misspelt keys, ids and enum values.
#include <string>
#include <string_view>
#include <vector>

namespace orch {

std::size_t edit_distance(std::string_view a, std::string_view b);
// The closest of `choices` to `word` when it is plausibly a typo of it, else "".
std::string closest_match(std::string_view word, const std::vector<std::string>& choices);
// " (did you mean \"x\"?)" or "".
std::string did_you_mean(std::string_view word, const std::vector<std::string>& choices);
// "a", "b" or "c"  -- for "expected one of ..." messages.
std::string quoted_list(const std::vector<std::string>& items);

}  // namespace orch
