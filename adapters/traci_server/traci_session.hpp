#pragma once
// One plug-in's TraCI conversation, without sockets: message bodies in, reply messages out.
// It answers queries from the world, forwards the ego's commands, keeps the plug-in's
// subscriptions, and stops at every simulationStep so that the orchestrator (and nobody
// else) advances the world. The Asio server (traci_ego_link.cpp) carries the bytes.
//
// Lockstep: handle() processes a message's commands in order. At a simulationStep it returns
// Next::Step; the orchestrator advances the world until target() and calls resume(), which
// writes the step's reply (with the subscription results, as SUMO does) and goes on with the
// rest of the message.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "traci_server/ego_world.hpp"
#include "traci_server/traci_wire.hpp"

namespace orch::traci {

struct SessionStats {
  std::map<std::string, long long> commands;  // "vehicle.setSpeed" -> count
  std::string client;                         // simulation parameter "orch.client", if set
  std::optional<int> order;                   // setOrder, if sent
};

class Session {
 public:
  enum class Next {
    Reply,  // take_reply() and wait for the plug-in's next message
    Step,   // advance the world until target(), then resume()
    Close,  // take_reply() (the answer to close), then close the connection
  };

  Session(EgoWorld& world, std::string server_version);

  // Handles one message body (without its 4-byte length). Throws DecodeError for malformed
  // input; take_reply() then holds the answers so far and an error status.
  Next handle(std::string_view body);
  // The world reached target() (or the run ended): answers the simulationStep and goes on.
  Next resume();
  // The whole reply message (length included) and a fresh one begins.
  std::string take_reply();

  // The scenario run is over: from now on simulationStep gets an error with this text and
  // getMinExpectedNumber says 0, so a plug-in's usual loop ends by itself.
  void end_run(std::string why) { ended_ = std::move(why); }

  [[nodiscard]] bool stepping() const { return stepping_; }
  [[nodiscard]] double target() const { return target_; }
  // Counts by name; built on request (naming every command as it comes costs per step).
  [[nodiscard]] SessionStats stats() const;

 private:
  struct VarRequest {
    std::uint8_t variable = 0;
    std::optional<Value> parameter;
  };
  struct Subscription {
    std::uint8_t command = 0;  // CMD_SUBSCRIBE_*_VARIABLE or CMD_SUBSCRIBE_*_CONTEXT
    Domain domain = Domain::Vehicle;
    std::string id;
    double begin = 0, end = 0;
    std::vector<VarRequest> vars;
    bool context = false;
    std::uint8_t context_domain_cmd = 0;  // CMD_GET_*_VARIABLE of the objects around
    Domain context_domain = Domain::Vehicle;
    double range = 0;
    bool ended = false;  // expired, or its object left: dropped after this step's results
  };

  Next run_commands();
  void dispatch(const RawCommand& c);
  void count(std::uint8_t command, int variable);
  void status(std::uint8_t command, std::uint8_t result, std::string_view text = {});

  void get_version();
  void get_variable(const RawCommand& c, Domain domain);
  Value read_variable(Domain domain, std::uint8_t variable, const std::string& id, const std::optional<Value>& parameter);
  void set_vehicle(const RawCommand& c);
  void set_simulation(const RawCommand& c);
  bool begin_step(const RawCommand& c);  // true: the world must advance

  // Subscriptions (traci_subscriptions.cpp).
  void subscribe(const RawCommand& c, Domain domain, bool context);
  std::vector<VarRequest> read_var_requests(Reader& r, Domain domain);
  [[nodiscard]] bool active(const Subscription& s, double now) const;
  // Appends one subscription's result command; false when its object is gone.
  bool append_result(std::string& out, const Subscription& s);
  void append_values(Writer& w, Domain domain, const std::string& id, const std::vector<VarRequest>& vars);
  std::vector<std::string> objects_in_range(const Subscription& s);
  void append_step_results();

  EgoWorld& world_;
  std::string server_version_;
  SessionStats stats_;  // client and order; the counts live in counts_
  std::map<std::pair<int, int>, long long> counts_;  // (command id, variable) -> how often
  std::vector<Subscription> subscriptions_;

  // The message being handled; commands_ point into message_.
  std::string message_;
  std::vector<RawCommand> commands_;
  std::size_t next_ = 0;
  std::string reply_;  // body of the reply under construction

  bool stepping_ = false;
  double target_ = 0;
  bool closing_ = false;
  std::optional<std::string> ended_;
};

// Domain and name of a TraCI command, for messages and the counts in result.json.
std::string command_name(std::uint8_t command, int variable);

}  // namespace orch::traci
