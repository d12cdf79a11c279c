#include "traci_server/traci_session.hpp"

#include "traci_server/traci_variables.hpp"

#include <libsumo/TraCIConstants.h>

#include <cmath>
#include <cstdio>

namespace orch::traci {

namespace tc = libsumo;

namespace {

constexpr double kTimeEps = 1e-6;  // s; simulation times are multiples of the step

std::string hex2(unsigned v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02x", v & 0xFFu);
  return buf;
}

const char* domain_of_command(std::uint8_t c) {
  static constexpr const char* names[] = {"inductionloop", "multientryexit", "trafficlight", "lane",
                                          "vehicle",       "vehicletype",    "route",        "poi",
                                          "polygon",       "junction",       "edge",         "simulation",
                                          "gui",           "lanearea",       "person",       "calibrator"};
  const int kind = c >> 4;
  // get 0xa_, set 0xc_, subscribe 0xd_, context 0x8_ share the domain in the low nibble.
  if (kind != 0xa && kind != 0xc && kind != 0xd && kind != 0x8) return nullptr;
  return names[c & 0x0F];
}

std::string named(const char* name, int variable, const char* fallback) {
  return name ? std::string(name) : std::string(fallback) + " " + hex2(static_cast<unsigned>(variable));
}

}  // namespace

std::string command_name(std::uint8_t command, int variable) {
  switch (command) {
    case tc::CMD_GETVERSION: return "getVersion";
    case tc::CMD_SIMSTEP: return "simulationStep";
    case tc::CMD_SETORDER: return "setOrder";
    case tc::CMD_CLOSE: return "close";
    default: break;
  }
  const char* domain = domain_of_command(command);
  const std::string prefix = domain ? std::string(domain) + "." : "command " + hex2(command) + ".";
  switch (command & 0xF0) {
    case 0xa0:
      return prefix + named(getter_name(command == tc::CMD_GET_SIM_VARIABLE, variable), variable, "get");
    case 0xc0:
      if (command == tc::CMD_SET_SIM_VARIABLE && variable == tc::VAR_PARAMETER) return prefix + "setParameter";
      return prefix + named(setter_name(variable), variable, "set");
    case 0xd0: return prefix + "subscribe";
    case 0x80: return prefix + "subscribeContext";
    default: return "command " + hex2(command);
  }
}

Session::Session(EgoWorld& world, std::string server_version)
    : world_(world), server_version_(std::move(server_version)) {}

std::string Session::take_reply() {
  std::string out = frame_message(reply_);
  reply_.clear();
  return out;
}

void Session::status(std::uint8_t command, std::uint8_t result, std::string_view text) {
  append_status(reply_, command, result, text);
}

void Session::count(std::uint8_t command, int variable) { ++counts_[{command, variable}]; }

SessionStats Session::stats() const {
  SessionStats s = stats_;
  for (const auto& [key, n] : counts_) s.commands[command_name(static_cast<std::uint8_t>(key.first), key.second)] += n;
  return s;
}

Session::Next Session::handle(std::string_view body) {
  message_.assign(body);
  next_ = 0;
  try {
    commands_ = split_commands(message_);
  } catch (const DecodeError& e) {
    commands_.clear();
    // No command can be trusted; the answer carries the error under command id 0.
    status(0, tc::RTYPE_ERR, std::string("malformed message: ") + e.what());
    throw;
  }
  return run_commands();
}

Session::Next Session::resume() {
  stepping_ = false;
  status(tc::CMD_SIMSTEP, tc::RTYPE_OK);
  append_step_results();
  return run_commands();
}

Session::Next Session::run_commands() {
  while (next_ < commands_.size()) {
    const RawCommand& c = commands_[next_++];
    if (c.id == tc::CMD_SIMSTEP) {
      count(c.id, -1);
      if (begin_step(c)) return Next::Step;
      continue;
    }
    try {
      dispatch(c);
    } catch (const DecodeError& e) {
      status(c.id, tc::RTYPE_ERR, std::string("malformed ") + command_name(c.id, -1) + ": " + e.what());
      throw;
    }
    if (closing_) return Next::Close;
  }
  return Next::Reply;
}

bool Session::begin_step(const RawCommand& c) {
  Reader r(c.content);
  double requested = 0;
  try {
    requested = r.float64();
  } catch (const DecodeError& e) {
    status(c.id, tc::RTYPE_ERR, std::string("malformed simulationStep: ") + e.what());
    throw;
  }
  if (ended_) {
    status(c.id, tc::RTYPE_ERR, *ended_);
    return false;
  }
  const double now = std::get<double>(world_.read(Domain::Simulation, tc::VAR_TIME, "", std::nullopt));
  if (requested == 0) {
    const double dt = std::get<double>(world_.read(Domain::Simulation, tc::VAR_DELTA_T, "", std::nullopt));
    target_ = now + dt;
  } else if (!(requested > now + kTimeEps)) {
    // As SUMO: a target time not after now performs no step; the reply comes at once.
    status(c.id, tc::RTYPE_OK);
    append_step_results();
    return false;
  } else {
    target_ = requested;
  }
  stepping_ = true;
  return true;
}

void Session::dispatch(const RawCommand& c) {
  Reader r(c.content);
  switch (c.id) {
    case tc::CMD_GETVERSION:
      count(c.id, -1);
      get_version();
      return;
    case tc::CMD_SETORDER:
      count(c.id, -1);
      stats_.order = r.int32();
      status(c.id, tc::RTYPE_OK);
      return;
    case tc::CMD_CLOSE:
      count(c.id, -1);
      status(c.id, tc::RTYPE_OK);
      closing_ = true;
      return;
    case tc::CMD_GET_VEHICLE_VARIABLE: return get_variable(c, Domain::Vehicle);
    case tc::CMD_GET_PERSON_VARIABLE: return get_variable(c, Domain::Person);
    case tc::CMD_GET_SIM_VARIABLE: return get_variable(c, Domain::Simulation);
    case tc::CMD_SET_VEHICLE_VARIABLE: return set_vehicle(c);
    case tc::CMD_SET_SIM_VARIABLE: return set_simulation(c);
    case tc::CMD_SUBSCRIBE_VEHICLE_VARIABLE: return subscribe(c, Domain::Vehicle, false);
    case tc::CMD_SUBSCRIBE_PERSON_VARIABLE: return subscribe(c, Domain::Person, false);
    case tc::CMD_SUBSCRIBE_SIM_VARIABLE: return subscribe(c, Domain::Simulation, false);
    case tc::CMD_SUBSCRIBE_VEHICLE_CONTEXT: return subscribe(c, Domain::Vehicle, true);
    case tc::CMD_SUBSCRIBE_PERSON_CONTEXT: return subscribe(c, Domain::Person, true);
    default: {
      const int variable = c.content.empty() ? -1 : static_cast<std::uint8_t>(c.content[0]);
      count(c.id, variable);
      status(c.id, tc::RTYPE_NOTIMPLEMENTED,
             command_name(c.id, variable) + " is not implemented by the orchestrator's ego TraCI server");
      return;
    }
  }
}

void Session::get_version() {
  Writer w;
  w.int32(tc::TRACI_VERSION);
  w.string(server_version_);
  status(tc::CMD_GETVERSION, tc::RTYPE_OK);
  append_command(reply_, tc::CMD_GETVERSION, w.bytes());
}

Value Session::read_variable(Domain domain, std::uint8_t variable, const std::string& id,
                             const std::optional<Value>& parameter) {
  if (domain == Domain::Simulation && variable == tc::VAR_MIN_EXPECTED_VEHICLES) {
    // While the run goes on at least the ego is expected, whatever SUMO counts; afterwards
    // nothing is, so `while getMinExpectedNumber() > 0` loops end with the run.
    if (ended_) return std::int32_t{0};
    const Value v = world_.read(domain, variable, id, parameter);
    return std::max<std::int32_t>(1, std::get<std::int32_t>(v));
  }
  if (variable == tc::VAR_PARAMETER_WITH_KEY) {
    if (!parameter || !std::holds_alternative<std::string>(*parameter))
      throw DecodeError("getParameterWithKey needs the key as a string");
    const Value v = world_.read(domain, tc::VAR_PARAMETER, id, parameter);
    return KeyValue{std::get<std::string>(*parameter), std::get<std::string>(v)};
  }
  return world_.read(domain, variable, id, parameter);
}

void Session::get_variable(const RawCommand& c, Domain domain) {
  Reader r(c.content);
  const std::uint8_t variable = r.ubyte();
  const std::string id = r.string();
  count(c.id, variable);
  std::optional<Value> parameter;
  if (r.remaining() > 0) parameter = r.typed_value("the get command's parameter");
  if ((variable == tc::VAR_PARAMETER || variable == tc::VAR_LEADER) && !parameter)
    throw DecodeError(command_name(c.id, variable) + " needs its parameter");
  try {
    const Value v = read_variable(domain, variable, id, parameter);
    Writer w;
    w.ubyte(variable);
    w.string(id);
    w.typed(v);
    status(c.id, tc::RTYPE_OK);
    append_command(reply_, static_cast<std::uint8_t>(c.id + 0x10), w.bytes());
  } catch (const NotImplemented& e) {
    status(c.id, tc::RTYPE_NOTIMPLEMENTED, e.what());
  } catch (const WorldError& e) {
    status(c.id, tc::RTYPE_ERR, e.what());
  }
}

void Session::set_vehicle(const RawCommand& c) {
  Reader r(c.content);
  const std::uint8_t variable = r.ubyte();
  const std::string id = r.string();
  count(c.id, variable);
  if (setter_name(variable) == nullptr) {
    status(c.id, tc::RTYPE_NOTIMPLEMENTED,
           command_name(c.id, variable) + " is not implemented by the orchestrator's ego TraCI server");
    return;
  }
  EgoCommand command;
  switch (variable) {
    case tc::VAR_SPEED: command = SetSpeed{r.typed_double("speed")}; break;
    case tc::CMD_SLOWDOWN: {
      if (r.compound("slowDown") != 2) throw DecodeError("slowDown takes 2 items (speed, duration)");
      SlowDown s;
      s.speed = r.typed_double("slowDown speed");
      s.duration = r.typed_double("slowDown duration");
      command = s;
      break;
    }
    case tc::CMD_CHANGELANE: {
      const std::int32_t items = r.compound("changeLane");
      if (items != 2 && items != 3) throw DecodeError("changeLane takes 2 or 3 items (lane, duration[, relative])");
      ChangeLane s;
      s.lane = r.typed_byte("changeLane lane");
      s.duration = r.typed_double("changeLane duration");
      if (items == 3 && r.typed_byte("changeLane relative flag") != 0) {
        if (id != "ego") break;  // refused below; do not read another vehicle
        try {
          s.lane += std::get<std::int32_t>(world_.read(Domain::Vehicle, tc::VAR_LANE_INDEX, id, std::nullopt));
        } catch (const WorldError& e) {
          status(c.id, tc::RTYPE_ERR, e.what());
          return;
        }
      }
      command = s;
      break;
    }
    case tc::MOVE_TO_XY: {
      const std::int32_t items = r.compound("moveToXY");
      if (items != 6 && items != 7) throw DecodeError("moveToXY takes 6 or 7 items");
      MoveToXY m;
      m.edge = r.typed_string("moveToXY edge");
      m.lane = r.typed_int("moveToXY lane");
      m.x = r.typed_double("moveToXY x");
      m.y = r.typed_double("moveToXY y");
      m.angle = r.typed_double("moveToXY angle");
      m.keep_route = r.typed_byte("moveToXY keepRoute");
      if (items == 7) m.match_threshold = r.typed_double("moveToXY matchThreshold");
      command = m;
      break;
    }
    case tc::VAR_SIGNALS: command = SetSignals{r.typed_int("signals")}; break;
    case tc::VAR_SPEEDSETMODE: command = SetSpeedMode{r.typed_int("speed mode")}; break;
    default: command = SetLaneChangeMode{r.typed_int("lane change mode")}; break;
  }
  if (id != "ego") {
    status(c.id, tc::RTYPE_ERR,
           "the ego plug-in may command only the vehicle 'ego', not '" + id + "' (the scenario drives the others)");
    return;
  }
  try {
    world_.command(id, command);
    status(c.id, tc::RTYPE_OK);
  } catch (const WorldError& e) {
    status(c.id, tc::RTYPE_ERR, e.what());
  }
}

void Session::set_simulation(const RawCommand& c) {
  Reader r(c.content);
  const std::uint8_t variable = r.ubyte();
  r.string();  // the simulation has no object id
  count(c.id, variable);
  if (variable == tc::VAR_PARAMETER) {
    if (r.compound("setParameter") != 2) throw DecodeError("setParameter takes 2 items (key, value)");
    const std::string key = r.typed_string("parameter key");
    const std::string value = r.typed_string("parameter value");
    if (key == "orch.client") {
      // TraCI's getVersion carries nothing about the client: this is how a plug-in names itself.
      stats_.client = value.substr(0, 200);
      status(c.id, tc::RTYPE_OK);
      return;
    }
  }
  status(c.id, tc::RTYPE_NOTIMPLEMENTED,
         command_name(c.id, variable) + " is not implemented by the orchestrator's ego TraCI server");
}

}  // namespace orch::traci
