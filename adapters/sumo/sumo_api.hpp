#pragma once
// SUMO's C++ client API as one namespace, whichever library this source is compiled for.
// libsumo and libtraci declare their classes (Simulation, Vehicle, ...) in namespace
// `libsumo` or `libtraci` (ORCH_SUMO_NS, adapters/CMakeLists.txt), but both keep the shared
// types and exceptions (TraCIPosition, TraCIException, FatalTraCIError, ...) in `libsumo`.
// `orch_sumo::X` finds either, so one adapter source compiles for both:
//   namespace sumo = orch_sumo;  sumo::Vehicle::getSpeed(id);  catch (sumo::TraCIException&)
#include ORCH_SUMO_HEADER

#include <libsumo/TraCIConstants.h>

// A name made per client library (for what two sources of one library share).
#define ORCH_SUMO_CONCAT_INNER(a, b) a##b
#define ORCH_SUMO_CONCAT(a, b) ORCH_SUMO_CONCAT_INNER(a, b)

namespace orch_sumo {
using namespace ORCH_SUMO_NS;  // NOLINT: the classes of this compilation's library
using libsumo::ContextSubscriptionResults;
using libsumo::FatalTraCIError;
using libsumo::SubscriptionResults;
using libsumo::TraCIColor;
using libsumo::TraCIDouble;
using libsumo::TraCIException;
using libsumo::TraCIInt;
using libsumo::TraCIPosition;
using libsumo::TraCIResult;
using libsumo::TraCIResults;
using libsumo::TraCIString;
using libsumo::TraCIStringList;
}  // namespace orch_sumo
