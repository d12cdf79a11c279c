# Turns a text file into a C++ source defining `std::string_view NAME()`, so that data the
# binary cannot run without (the vehicle catalog) travels inside it.
# Usage: cmake -DINPUT=... -DOUTPUT=... -DNAME=... -P embed_file.cmake
file(READ "${INPUT}" content)
set(delim "orch_embed")
file(WRITE "${OUTPUT}" "// Generated from ${INPUT}; do not edit.\n#include <string_view>\nnamespace orch::embedded {\nstd::string_view ${NAME}() {\n  static constexpr std::string_view text = R\"${delim}(${content})${delim}\";\n  return text;\n}\n}  // namespace orch::embedded\n")
