#pragma once
// Making the files SUMO's tools write reproducible.
#include <string>

namespace orch {

// netconvert stamps its output with the time of the run ("<!-- generated on 2024-05-01
// 12:00:00 by Eclipse SUMO netconvert ..."); this drops the timestamp so that the same
// inputs give the same bytes. Everything else netconvert writes is already deterministic.
std::string without_generation_date(std::string net);

}  // namespace orch
