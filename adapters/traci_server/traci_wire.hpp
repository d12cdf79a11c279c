#pragma once
// TraCI's wire format (SUMO 1.15, API 20), as far as the ego server needs it: big-endian
// numbers, length-prefixed strings, typed values, messages and commands in both length
// forms. Every read is bounds-checked: hostile input ends in DecodeError, never in an
// out-of-range read or a huge allocation.
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace orch::traci {

// Malformed input (bad length, truncated command, wrong type tag). The connection cannot be
// trusted to stay in sync afterwards, so it is closed.
class DecodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A message may not be larger than this (its 4-byte length included): a plug-in sends
// commands of a few dozen bytes, and a claimed 2 GB must not become a 2 GB allocation.
inline constexpr std::size_t kMaxMessageBytes = 1u << 20;

// ------------------------------------------------------------------ values
struct Pos2 {
  double x = 0, y = 0;
};
struct Pos3 {
  double x = 0, y = 0, z = 0;
};
struct Leader {  // VAR_LEADER: compound of the leader's id ("" none) and the gap, m
  std::string id;
  double gap = 0;
};
struct Color {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
};
struct KeyValue {  // VAR_PARAMETER_WITH_KEY: compound of key and value
  std::string key;
  std::string value;
};
// One typed value as TraCI sends it. int32 and double are TYPE_INTEGER and TYPE_DOUBLE.
using Value =
    std::variant<std::int32_t, double, std::string, std::vector<std::string>, Pos2, Pos3, Leader, Color, KeyValue>;

// ------------------------------------------------------------------ reading
class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}

  std::uint8_t ubyte();
  std::int8_t byte();
  std::int32_t int32();
  double float64();
  std::string string();
  std::vector<std::string> string_list();

  // A type tag followed by its value; `what` names the value in the error message.
  std::int32_t typed_int(const char* what);
  double typed_double(const char* what);
  std::string typed_string(const char* what);
  std::uint8_t typed_ubyte(const char* what);
  std::int8_t typed_byte(const char* what);
  std::int32_t compound(const char* what);  // returns the item count
  // Any typed value of a kind Value can hold (a parameter of a get or subscription).
  Value typed_value(const char* what);

  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - pos_; }

 private:
  std::string_view take(std::size_t n, const char* what);
  void expect_type(std::uint8_t want, const char* what);

  std::string_view bytes_;
  std::size_t pos_ = 0;
};

// ------------------------------------------------------------------ writing
class Writer {
 public:
  void ubyte(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
  void byte(std::int8_t v) { out_.push_back(static_cast<char>(v)); }
  void int32(std::int32_t v);
  void float64(double v);
  void string(std::string_view s);
  void string_list(const std::vector<std::string>& items);
  void typed(const Value& v);  // type tag and value
  void raw(std::string_view bytes) { out_.append(bytes); }

  [[nodiscard]] const std::string& bytes() const { return out_; }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

// ------------------------------------------------------------------ framing
// The body length (without the 4 header bytes) a message header announces. Throws
// DecodeError for a length below 4 or above `limit`.
std::size_t message_body_length(const std::array<std::uint8_t, 4>& header, std::size_t limit = kMaxMessageBytes);

struct RawCommand {
  std::uint8_t id = 0;
  std::string_view content;  // after the command id
};
// Splits a message body into its commands (short form: 1-byte length; long form: 0, then a
// 4-byte length). Throws DecodeError when a command's length does not fit the message.
std::vector<RawCommand> split_commands(std::string_view body);

// Appends one command (length, id, content), in the short form when it fits.
void append_command(std::string& out, std::uint8_t id, std::string_view content);
// Appends a status response. Descriptions are cut to fit the short length form: SUMO's own
// Python client reads status responses as three single bytes.
void append_status(std::string& out, std::uint8_t id, std::uint8_t result, std::string_view description);
// A whole message: 4-byte length, then the body.
std::string frame_message(std::string_view body);

}  // namespace orch::traci
