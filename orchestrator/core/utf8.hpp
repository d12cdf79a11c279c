#pragma once
// Text the program writes (result files, logs, XML, the terminal) must be valid UTF-8
// whatever bytes came in: file names from argv, the "last read" bytes nlohmann quotes in a
// parse error, a child's stderr. Ill-formed sequences become U+FFFD, never a failed write.
#include <string>
#include <string_view>

namespace orch {

// True when `text` is well-formed UTF-8 (no overlong forms, surrogates or code points
// above U+10FFFF).
bool is_valid_utf8(std::string_view text);

// `text` with every ill-formed byte sequence replaced by U+FFFD (one per maximal invalid
// subpart, as the Unicode standard recommends); valid text is returned unchanged.
std::string valid_utf8(std::string_view text);

}  // namespace orch
