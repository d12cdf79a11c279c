#pragma once
// One pass over the bytes of a JSON text, skipping strings: for the checks that must run
// before (or instead of) a parse, in time linear in the text and without recursion.
#include <cstddef>
#include <string>

namespace orch {

// Calls f(offset, c) for every byte of `text` outside string literals (escapes included).
template <class F>
void for_each_outside_strings(const std::string& text, F&& f) {
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else {
      f(i, c);
    }
  }
}

}  // namespace orch
