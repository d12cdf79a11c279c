#pragma once
// JSON text for every file and line the program writes. nlohmann's dump() throws on a
// string holding invalid UTF-8 (type_error 316), which would lose the whole result file; the
// `replace` handler writes U+FFFD instead. Use this, never dump() directly, for output.
#include <nlohmann/json.hpp>
#include <string>

namespace orch {

// `indent` as for dump(): -1 is one line, n >= 0 pretty-prints with n spaces.
template <class Json>
std::string json_text(const Json& value, int indent = -1) {
  return value.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace orch
