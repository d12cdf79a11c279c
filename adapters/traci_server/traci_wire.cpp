#include "traci_server/traci_wire.hpp"

#include <libsumo/TraCIConstants.h>

#include <bit>
#include <cstring>
#include <string>

namespace orch::traci {

namespace tc = libsumo;

namespace {

std::string hex(unsigned v) {
  static constexpr char digits[] = "0123456789abcdef";
  return std::string("0x") + digits[(v >> 4) & 0xF] + digits[v & 0xF];
}

std::uint32_t load_be32(const char* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<std::uint8_t>(p[i]);
  return v;
}

}  // namespace

// ------------------------------------------------------------------ Reader
std::string_view Reader::take(std::size_t n, const char* what) {
  if (n > remaining())
    throw DecodeError(std::string("truncated ") + what + ": needs " + std::to_string(n) + " byte(s), " +
                      std::to_string(remaining()) + " left in the command");
  const std::string_view s = bytes_.substr(pos_, n);
  pos_ += n;
  return s;
}

std::uint8_t Reader::ubyte() { return static_cast<std::uint8_t>(take(1, "byte")[0]); }
std::int8_t Reader::byte() { return static_cast<std::int8_t>(take(1, "byte")[0]); }

std::int32_t Reader::int32() { return static_cast<std::int32_t>(load_be32(take(4, "integer").data())); }

double Reader::float64() {
  const std::string_view s = take(8, "double");
  std::uint64_t bits = 0;
  for (char c : s) bits = (bits << 8) | static_cast<std::uint8_t>(c);
  return std::bit_cast<double>(bits);
}

std::string Reader::string() {
  const std::int32_t n = int32();
  if (n < 0) throw DecodeError("negative string length " + std::to_string(n));
  return std::string(take(static_cast<std::size_t>(n), "string"));
}

std::vector<std::string> Reader::string_list() {
  const std::int32_t n = int32();
  // Each item needs at least its 4-byte length: a count beyond that is a lie, not a reason
  // to reserve memory.
  if (n < 0 || static_cast<std::size_t>(n) > remaining() / 4)
    throw DecodeError("string list of " + std::to_string(n) + " items does not fit the command");
  std::vector<std::string> out;
  out.reserve(static_cast<std::size_t>(n));
  for (std::int32_t i = 0; i < n; ++i) out.push_back(string());
  return out;
}

void Reader::expect_type(std::uint8_t want, const char* what) {
  const std::uint8_t got = ubyte();
  if (got != want) throw DecodeError(std::string(what) + " must have type " + hex(want) + ", got " + hex(got));
}

std::int32_t Reader::typed_int(const char* what) {
  expect_type(tc::TYPE_INTEGER, what);
  return int32();
}
double Reader::typed_double(const char* what) {
  expect_type(tc::TYPE_DOUBLE, what);
  return float64();
}
std::string Reader::typed_string(const char* what) {
  expect_type(tc::TYPE_STRING, what);
  return string();
}
std::uint8_t Reader::typed_ubyte(const char* what) {
  expect_type(tc::TYPE_UBYTE, what);
  return ubyte();
}
std::int8_t Reader::typed_byte(const char* what) {
  expect_type(tc::TYPE_BYTE, what);
  return byte();
}
std::int32_t Reader::compound(const char* what) {
  expect_type(tc::TYPE_COMPOUND, what);
  return int32();
}

Value Reader::typed_value(const char* what) {
  const std::uint8_t type = ubyte();
  switch (type) {
    case tc::TYPE_INTEGER: return int32();
    case tc::TYPE_DOUBLE: return float64();
    case tc::TYPE_STRING: return string();
    case tc::TYPE_STRINGLIST: return string_list();
    case tc::TYPE_BYTE: return static_cast<std::int32_t>(byte());
    case tc::TYPE_UBYTE: return static_cast<std::int32_t>(ubyte());
    case tc::POSITION_2D: {
      Pos2 p;
      p.x = float64();
      p.y = float64();
      return p;
    }
    case tc::POSITION_3D: {
      Pos3 p;
      p.x = float64();
      p.y = float64();
      p.z = float64();
      return p;
    }
    default: throw DecodeError(std::string(what) + " has unsupported type " + hex(type));
  }
}

// ------------------------------------------------------------------ Writer
void Writer::int32(std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  for (int shift = 24; shift >= 0; shift -= 8) ubyte(static_cast<std::uint8_t>(u >> shift));
}

void Writer::float64(double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  for (int shift = 56; shift >= 0; shift -= 8) ubyte(static_cast<std::uint8_t>(bits >> shift));
}

void Writer::string(std::string_view s) {
  int32(static_cast<std::int32_t>(s.size()));
  out_.append(s);
}

void Writer::string_list(const std::vector<std::string>& items) {
  int32(static_cast<std::int32_t>(items.size()));
  for (const auto& s : items) string(s);
}

void Writer::typed(const Value& v) {
  std::visit(
      [this](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::int32_t>) {
          ubyte(tc::TYPE_INTEGER);
          int32(x);
        } else if constexpr (std::is_same_v<T, double>) {
          ubyte(tc::TYPE_DOUBLE);
          float64(x);
        } else if constexpr (std::is_same_v<T, std::string>) {
          ubyte(tc::TYPE_STRING);
          string(x);
        } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
          ubyte(tc::TYPE_STRINGLIST);
          string_list(x);
        } else if constexpr (std::is_same_v<T, Pos2>) {
          ubyte(tc::POSITION_2D);
          float64(x.x);
          float64(x.y);
        } else if constexpr (std::is_same_v<T, Pos3>) {
          ubyte(tc::POSITION_3D);
          float64(x.x);
          float64(x.y);
          float64(x.z);
        } else if constexpr (std::is_same_v<T, Leader>) {
          ubyte(tc::TYPE_COMPOUND);
          int32(2);
          ubyte(tc::TYPE_STRING);
          string(x.id);
          ubyte(tc::TYPE_DOUBLE);
          float64(x.gap);
        } else if constexpr (std::is_same_v<T, KeyValue>) {
          ubyte(tc::TYPE_COMPOUND);
          int32(2);
          ubyte(tc::TYPE_STRING);
          string(x.key);
          ubyte(tc::TYPE_STRING);
          string(x.value);
        } else {
          static_assert(std::is_same_v<T, Color>);
          ubyte(tc::TYPE_COLOR);
          ubyte(x.r);
          ubyte(x.g);
          ubyte(x.b);
          ubyte(x.a);
        }
      },
      v);
}

// ------------------------------------------------------------------ framing
std::size_t message_body_length(const std::array<std::uint8_t, 4>& header, std::size_t limit) {
  const std::uint32_t total = (std::uint32_t{header[0]} << 24) | (std::uint32_t{header[1]} << 16) |
                              (std::uint32_t{header[2]} << 8) | std::uint32_t{header[3]};
  if (total < 4) throw DecodeError("message length " + std::to_string(total) + " is shorter than its own header");
  if (total > limit)
    throw DecodeError("message length " + std::to_string(total) + " exceeds the limit of " + std::to_string(limit) +
                      " bytes");
  return total - 4;
}

std::vector<RawCommand> split_commands(std::string_view body) {
  std::vector<RawCommand> out;
  std::size_t pos = 0;
  while (pos < body.size()) {
    const std::size_t start = pos;
    std::size_t length = static_cast<std::uint8_t>(body[pos]);
    std::size_t header = 1;
    if (length == 0) {
      if (body.size() - pos < 5) throw DecodeError("truncated command: long length form without its 4-byte length");
      length = load_be32(body.data() + pos + 1);
      header = 5;
    }
    // The length counts its own bytes and the command id.
    if (length < header + 1)
      throw DecodeError("command length " + std::to_string(length) + " leaves no room for the command id");
    if (length > body.size() - start)
      throw DecodeError("truncated command: length " + std::to_string(length) + ", but only " +
                        std::to_string(body.size() - start) + " byte(s) left in the message");
    RawCommand c;
    c.id = static_cast<std::uint8_t>(body[start + header]);
    c.content = body.substr(start + header + 1, length - header - 1);
    out.push_back(c);
    pos = start + length;
  }
  return out;
}

void append_command(std::string& out, std::uint8_t id, std::string_view content) {
  Writer w;
  if (content.size() + 2 <= 255) {
    w.ubyte(static_cast<std::uint8_t>(content.size() + 2));
  } else {
    w.ubyte(0);
    w.int32(static_cast<std::int32_t>(content.size() + 6));
  }
  w.ubyte(id);
  out += w.bytes();
  out.append(content);
}

void append_status(std::string& out, std::uint8_t id, std::uint8_t result, std::string_view description) {
  // 1 length + 1 id + 1 result + 4 string length + text <= 255.
  constexpr std::size_t kMaxText = 255 - 7;
  if (description.size() > kMaxText) description = description.substr(0, kMaxText);
  Writer w;
  w.ubyte(result);
  w.string(description);
  append_command(out, id, w.bytes());
}

std::string frame_message(std::string_view body) {
  Writer w;
  w.int32(static_cast<std::int32_t>(body.size() + 4));
  return w.take().append(body);
}

}  // namespace orch::traci
