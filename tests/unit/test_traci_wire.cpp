// TraCI's wire format: exact bytes, both length forms, and hostile lengths.
#include <gtest/gtest.h>

#include "traci_messages.hpp"

using namespace orch;
using namespace orch::test;
using traci::DecodeError;

namespace {
std::array<std::uint8_t, 4> header(std::uint32_t total) {
  return {static_cast<std::uint8_t>(total >> 24), static_cast<std::uint8_t>(total >> 16),
          static_cast<std::uint8_t>(total >> 8), static_cast<std::uint8_t>(total)};
}
}  // namespace

TEST(TraciWire, NumbersAndStringsAreBigEndianWithLengthPrefixes) {
  traci::Writer w;
  w.int32(0x01020304);
  w.float64(1.5);  // 0x3FF8000000000000
  w.string("ego");
  EXPECT_EQ(w.bytes(), std::string("\x01\x02\x03\x04\x3f\xf8\0\0\0\0\0\0\0\0\0\x03"
                                   "ego",
                                   19));
  traci::Reader r(w.bytes());
  EXPECT_EQ(r.int32(), 0x01020304);
  EXPECT_EQ(r.float64(), 1.5);
  EXPECT_EQ(r.string(), "ego");
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(TraciWire, TypedValuesCarryTheirTypeTags) {
  traci::Writer w;
  w.typed(std::int32_t{7});
  w.typed(traci::Pos2{1, 2});
  w.typed(traci::Leader{"actor1", 12.5});
  traci::Reader r(w.bytes());
  EXPECT_EQ(r.typed_int("i"), 7);
  EXPECT_EQ(r.ubyte(), tc::POSITION_2D);
  EXPECT_EQ(r.float64(), 1.0);
  EXPECT_EQ(r.float64(), 2.0);
  EXPECT_EQ(r.compound("leader"), 2);
  EXPECT_EQ(r.typed_string("id"), "actor1");
  EXPECT_EQ(r.typed_double("gap"), 12.5);
}

TEST(TraciWire, AWrongTypeTagIsADecodeError) {
  traci::Writer w;
  w.typed(std::int32_t{30});
  traci::Reader r(w.bytes());
  EXPECT_THROW(r.typed_double("speed"), DecodeError);
}

TEST(TraciWire, MessageLengthsBelowTheHeaderOrAboveTheLimitAreRefused) {
  EXPECT_THROW(traci::message_body_length(header(0)), DecodeError);
  EXPECT_THROW(traci::message_body_length(header(3)), DecodeError);
  EXPECT_EQ(traci::message_body_length(header(4)), 0u);
  EXPECT_EQ(traci::message_body_length(header(100)), 96u);
  EXPECT_THROW(traci::message_body_length(header(0x80000000u)), DecodeError);  // 2 GB
  EXPECT_THROW(traci::message_body_length(header(0xFFFFFFFFu)), DecodeError);
  EXPECT_THROW(traci::message_body_length(header(static_cast<std::uint32_t>(traci::kMaxMessageBytes + 1))), DecodeError);
}

TEST(TraciWire, CommandsSplitInBothLengthForms) {
  const std::string long_content(300, 'x');
  const std::string body = command(0x02, "abc") + command(0xa4, long_content);
  EXPECT_EQ(static_cast<std::uint8_t>(body[0]), 5);  // short form: length, id, 3 bytes
  const auto commands = traci::split_commands(body);
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_EQ(commands[0].id, 0x02);
  EXPECT_EQ(commands[0].content, "abc");
  EXPECT_EQ(commands[1].id, 0xa4);
  EXPECT_EQ(commands[1].content, long_content);
  EXPECT_EQ(body[5], '\0');  // long form starts with a zero
}

TEST(TraciWire, TruncatedOrImpossibleCommandsAreDecodeErrors) {
  const std::string good = command(0xa4, "abcdef");
  EXPECT_THROW(traci::split_commands(good.substr(0, good.size() - 1)), DecodeError);  // cut short
  EXPECT_THROW(traci::split_commands(std::string("\x01", 1)), DecodeError);          // no room for the id
  EXPECT_THROW(traci::split_commands(std::string("\x00\x00\x00", 3)), DecodeError);   // long form cut
  EXPECT_THROW(traci::split_commands(std::string("\x00\x00\x00\x00\x05\xa4", 6)), DecodeError);  // 5 < 6
  EXPECT_THROW(traci::split_commands(std::string("\x00\x7f\xff\xff\xff\xa4", 6)), DecodeError);  // 2 GB command
}

TEST(TraciWire, HostileStringAndListLengthsDoNotAllocate) {
  traci::Writer w;
  w.int32(-5);
  EXPECT_THROW(traci::Reader(w.bytes()).string(), DecodeError);
  traci::Writer list;
  list.int32(0x7FFFFFFF);  // claims two billion strings in a four-byte command
  EXPECT_THROW(traci::Reader(list.bytes()).string_list(), DecodeError);
  traci::Writer s;
  s.int32(1000);
  s.raw("short");
  EXPECT_THROW(traci::Reader(s.bytes()).string(), DecodeError);
}

TEST(TraciWire, StatusDescriptionsFitTheShortLengthFormThatPythonReads) {
  std::string out;
  traci::append_status(out, 0xc4, tc::RTYPE_ERR, std::string(1000, 'e'));
  ASSERT_EQ(out.size(), 255u);
  EXPECT_EQ(static_cast<std::uint8_t>(out[0]), 255);
  EXPECT_EQ(static_cast<std::uint8_t>(out[1]), 0xc4);
  EXPECT_EQ(static_cast<std::uint8_t>(out[2]), tc::RTYPE_ERR);
}
