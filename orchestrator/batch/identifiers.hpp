#pragma once
// UUIDs and timestamps for the ATLAS files (logical, parameter set, execution trace).
#include <string>
#include <string_view>

namespace orch::batch {

// A random (version 4) UUID, for things that happen once: an execution.
std::string random_uuid();
// A UUID that is a pure function of `name` (SHA-256 based, RFC 9562 version 8), so that
// sampling the same logical scenario with the same seed names its parameter set the same
// on every machine.
std::string name_based_uuid(std::string_view name);
// "2026-02-09T10:02:00Z": the current UTC time, as in the seed's files.
std::string utc_timestamp();
// True when `id` can name files safely: letters, digits, '-', '_' and '.', not starting
// with '.' (the seed's ids are UUIDs or short forms like "550e8400").
bool is_file_safe_id(std::string_view id);

}  // namespace orch::batch
