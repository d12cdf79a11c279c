#pragma once
// File helpers every writer of results uses: a result file is either the old one or the
// complete new one, never half written.
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace orch {

// Writes `content` to a temporary file beside `path`, flushes it to disk and renames it
// over `path`. Throws OrchError on failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);
// Whole file as a string; throws OrchError naming the file when it cannot be read.
std::string read_file(const std::filesystem::path& path);
// The rest of a file the caller opened (and reports problems with in its own words), at
// most `max_bytes` of it when the file's size is known.
std::string read_open_file(std::ifstream& in, const std::filesystem::path& path,
                           std::size_t max_bytes = std::string::npos);
// Lower-case hex SHA-256 of a file's bytes ("" when unreadable).
std::string sha256_of_file(const std::filesystem::path& path);
std::string sha256_hex(std::string_view bytes);

}  // namespace orch
