#pragma once
// xsd:dateTime as OpenSCENARIO writes it (TimeOfDay, TimeOfDayCondition, dateTime
// parameters): "YYYY-MM-DDThh:mm:ss", optional fractional seconds, optional time zone ("Z"
// or "+hh:mm" / "-hh:mm").
#include <optional>
#include <string_view>

namespace orch::openscenario {

// Seconds since 1970-01-01T00:00:00 UTC; a time without a zone is read as UTC (XML Schema
// leaves such a time "undetermined"; one file compares its times in one frame either way).
// nullopt when the text is no xsd:dateTime or names no real date or time.
std::optional<double> parse_date_time(std::string_view text);

// What an error says a dateTime should look like.
inline constexpr std::string_view kDateTimeForm =
    "xsd:dateTime (YYYY-MM-DDThh:mm:ss, optionally with fractional seconds and a zone such as Z or +01:00)";

}  // namespace orch::openscenario
