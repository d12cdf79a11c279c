// The plug-in's subscriptions: variable subscriptions (values of one object) and context
// subscriptions (objects of a domain within a range of one object: the plug-in's perception
// around the ego). Results go out with every simulationStep reply, as SUMO sends them.
#include <libsumo/TraCIConstants.h>

#include <algorithm>
#include <cmath>

#include "traci_server/traci_session.hpp"

namespace orch::traci {

namespace tc = libsumo;

namespace {

constexpr double kSubscriptionTimeEps = 1e-6;

bool takes_parameter(Domain domain, std::uint8_t variable) {
  return variable == tc::VAR_PARAMETER || variable == tc::VAR_PARAMETER_WITH_KEY ||
         (domain == Domain::Vehicle && variable == tc::VAR_LEADER);
}

const char* domain_word(Domain d) {
  switch (d) {
    case Domain::Vehicle: return "Vehicle";
    case Domain::Person: return "Person";
    case Domain::Simulation: return "Simulation";
  }
  return "Object";
}

std::optional<Domain> domain_of_get_command(std::uint8_t cmd) {
  if (cmd == tc::CMD_GET_VEHICLE_VARIABLE) return Domain::Vehicle;
  if (cmd == tc::CMD_GET_PERSON_VARIABLE) return Domain::Person;
  return std::nullopt;
}

}  // namespace

std::vector<Session::VarRequest> Session::read_var_requests(Reader& r, Domain domain) {
  const std::uint8_t n = r.ubyte();
  std::vector<VarRequest> vars;
  for (int i = 0; i < n; ++i) {
    VarRequest v;
    v.variable = r.ubyte();
    if (takes_parameter(domain, v.variable)) v.parameter = r.typed_value("the subscription's parameter");
    vars.push_back(std::move(v));
  }
  return vars;
}

void Session::subscribe(const RawCommand& c, Domain domain, bool context) {
  Reader r(c.content);
  count(c.id, -1);
  Subscription s;
  s.command = c.id;
  s.domain = domain;
  s.begin = r.float64();
  s.end = r.float64();
  s.id = r.string();
  s.context = context;
  Domain values_domain = domain;
  if (context) {
    s.context_domain_cmd = r.ubyte();
    s.range = r.float64();
    const auto d = domain_of_get_command(s.context_domain_cmd);
    if (!d) {
      status(c.id, tc::RTYPE_NOTIMPLEMENTED,
             "context subscriptions serve vehicles and persons only, not domain " + command_name(s.context_domain_cmd, -1));
      return;
    }
    s.context_domain = *d;
    values_domain = *d;
  }
  s.vars = read_var_requests(r, values_domain);

  const auto same = [&](const Subscription& o) {
    return o.command == s.command && o.id == s.id && (!context || o.context_domain_cmd == s.context_domain_cmd);
  };
  if (s.vars.empty()) {  // the clients' way to unsubscribe
    subscriptions_.erase(std::remove_if(subscriptions_.begin(), subscriptions_.end(), same), subscriptions_.end());
    status(c.id, tc::RTYPE_OK);
    return;
  }
  for (const auto& v : s.vars) {
    if (v.variable != tc::VAR_PARAMETER_WITH_KEY && !world_.supports(values_domain, v.variable)) {
      status(c.id, tc::RTYPE_NOTIMPLEMENTED,
             command_name(static_cast<std::uint8_t>((c.id & 0x0F) | 0xa0), v.variable) +
                 " cannot be subscribed: not implemented by the orchestrator's ego TraCI server");
      return;
    }
  }
  if (domain != Domain::Simulation && !world_.exists(domain, s.id)) {
    status(c.id, tc::RTYPE_ERR, std::string(domain_word(domain)) + " '" + s.id + "' is not known");
    return;
  }
  const auto it = std::find_if(subscriptions_.begin(), subscriptions_.end(), same);
  if (it != subscriptions_.end())
    *it = s;
  else
    subscriptions_.push_back(s);
  status(c.id, tc::RTYPE_OK);
  append_result(reply_, s);
}

bool Session::active(const Subscription& s, double now) const {
  const bool begun = s.begin == tc::INVALID_DOUBLE_VALUE || now + kSubscriptionTimeEps >= s.begin;
  const bool over = s.end != tc::INVALID_DOUBLE_VALUE && now > s.end + kSubscriptionTimeEps;
  return begun && !over;
}

void Session::append_values(Writer& w, Domain domain, const std::string& id, const std::vector<VarRequest>& vars) {
  for (const auto& v : vars) {
    w.ubyte(v.variable);
    try {
      const Value value = read_variable(domain, v.variable, id, v.parameter);
      w.ubyte(tc::RTYPE_OK);
      w.typed(value);
    } catch (const std::exception& e) {  // WorldError, NotImplemented, a bad parameter
      w.ubyte(tc::RTYPE_ERR);
      w.typed(std::string(e.what()));
    }
  }
}

std::vector<std::string> Session::objects_in_range(const Subscription& s) {
  std::vector<int> variables;
  for (const auto& v : s.vars) variables.push_back(v.variable);
  return world_.objects_in_range(s.domain, s.id, s.context_domain, s.range, variables);
}

bool Session::append_result(std::string& out, const Subscription& s) {
  if (s.domain != Domain::Simulation && !world_.exists(s.domain, s.id)) return false;
  Writer w;
  w.string(s.id);
  if (!s.context) {
    w.ubyte(static_cast<std::uint8_t>(s.vars.size()));
    append_values(w, s.domain, s.id, s.vars);
  } else {
    std::vector<std::string> near;
    try {
      near = objects_in_range(s);
    } catch (const WorldError&) {
      return false;
    }
    w.ubyte(s.context_domain_cmd);
    w.ubyte(static_cast<std::uint8_t>(s.vars.size()));
    w.int32(static_cast<std::int32_t>(near.size()));
    for (const auto& other : near) {
      w.string(other);
      append_values(w, s.context_domain, other, s.vars);
    }
  }
  append_command(out, static_cast<std::uint8_t>(s.command + 0x10), w.bytes());
  return true;
}

void Session::append_step_results() {
  const double now = std::get<double>(world_.read(Domain::Simulation, tc::VAR_TIME, "", std::nullopt));
  std::string results;
  std::int32_t n = 0;
  // Ended subscriptions are dropped in place once every result is written (no copy of every
  // subscription every step; a throw leaves the list as it was).
  bool any_ended = false;
  for (auto& s : subscriptions_) {
    if (s.end != tc::INVALID_DOUBLE_VALUE && now > s.end + kSubscriptionTimeEps) {
      s.ended = any_ended = true;  // expired
    } else if (active(s, now)) {
      // An object that left the simulation ends its subscription, as in SUMO.
      if (append_result(results, s)) ++n;
      else s.ended = any_ended = true;
    }
  }
  if (any_ended) std::erase_if(subscriptions_, [](const Subscription& s) { return s.ended; });
  Writer w;
  w.int32(n);
  reply_ += w.bytes();
  reply_ += results;
}

}  // namespace orch::traci
