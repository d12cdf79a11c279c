#pragma once
// The client's side of TraCI for tests: builds request messages the way SUMO's Python
// client does (connection.py) and splits replies into status responses and result commands.
#include <gtest/gtest.h>
#include <libsumo/TraCIConstants.h>

#include <string>
#include <vector>

#include "traci_server/traci_wire.hpp"

namespace orch::test {

namespace tc = libsumo;

// Content of a get command: variable, object id, optional typed parameter.
inline std::string get_content(int variable, const std::string& id) {
  traci::Writer w;
  w.ubyte(static_cast<std::uint8_t>(variable));
  w.string(id);
  return w.take();
}

inline std::string command(int id, const std::string& content) {
  std::string out;
  traci::append_command(out, static_cast<std::uint8_t>(id), content);
  return out;
}

inline std::string simstep(double target = 0) {
  traci::Writer w;
  w.float64(target);
  return command(tc::CMD_SIMSTEP, w.bytes());
}

inline std::string set_speed(const std::string& id, double speed) {
  traci::Writer w;
  w.ubyte(tc::VAR_SPEED);
  w.string(id);
  w.typed(speed);
  return command(tc::CMD_SET_VEHICLE_VARIABLE, w.bytes());
}

// A variable subscription as Python's traci sends it (begin/end "always").
inline std::string subscribe(int cmd, const std::string& id, const std::vector<int>& vars) {
  traci::Writer w;
  w.float64(tc::INVALID_DOUBLE_VALUE);
  w.float64(tc::INVALID_DOUBLE_VALUE);
  w.string(id);
  w.ubyte(static_cast<std::uint8_t>(vars.size()));
  for (int v : vars) w.ubyte(static_cast<std::uint8_t>(v));
  return command(cmd, w.bytes());
}

inline std::string subscribe_context(const std::string& id, int domain, double range, const std::vector<int>& vars) {
  traci::Writer w;
  w.float64(tc::INVALID_DOUBLE_VALUE);
  w.float64(tc::INVALID_DOUBLE_VALUE);
  w.string(id);
  w.ubyte(static_cast<std::uint8_t>(domain));
  w.float64(range);
  w.ubyte(static_cast<std::uint8_t>(vars.size()));
  for (int v : vars) w.ubyte(static_cast<std::uint8_t>(v));
  return command(tc::CMD_SUBSCRIBE_VEHICLE_CONTEXT, w.bytes());
}

struct Status {
  int command = -1;
  int result = -1;
  std::string text;
};

// Reads a reply message: strips the 4-byte length, then status responses and result
// commands in order. `reader` stays positioned for the caller to read results.
class Reply {
 public:
  explicit Reply(std::string message) : bytes_(std::move(message)), reader_(body()) {}

  std::string_view body() const {
    EXPECT_GE(bytes_.size(), 4u);
    const std::array<std::uint8_t, 4> header{static_cast<std::uint8_t>(bytes_[0]), static_cast<std::uint8_t>(bytes_[1]),
                                             static_cast<std::uint8_t>(bytes_[2]), static_cast<std::uint8_t>(bytes_[3])};
    EXPECT_EQ(traci::message_body_length(header), bytes_.size() - 4);
    return std::string_view(bytes_).substr(4);
  }
  Status status() {
    Status s;
    const int length = reader_.ubyte();
    s.command = reader_.ubyte();
    s.result = reader_.ubyte();
    s.text = reader_.string();
    EXPECT_EQ(length, 7 + static_cast<int>(s.text.size()));
    return s;
  }
  // A result command's header (length in either form, then id); returns the id.
  int result_command() {
    if (reader_.ubyte() == 0) reader_.int32();
    return reader_.ubyte();
  }
  traci::Reader& reader() { return reader_; }

 private:
  std::string bytes_;
  traci::Reader reader_;
};

}  // namespace orch::test
