// Fuzz target: arbitrary bytes as a plug-in's side of the connection (messages back to
// back), through the frame decoder and the TraCI session on a fake world. Whatever arrives,
// the server must either answer with a well-formed reply or report DecodeError (and close):
// no crash, no other exception, no read out of bounds, no allocation beyond the size limit.
// Built with libFuzzer (clang) and with a bounded random driver (random_driver.cpp).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "support/fake_ego_world.hpp"
#include "traci_server/traci_session.hpp"

namespace {

void check_reply(const std::string& reply) {
  // Every reply is one framed message whose length field is right.
  if (reply.size() < 4) std::abort();
  std::array<std::uint8_t, 4> header{};
  for (int i = 0; i < 4; ++i) header[i] = static_cast<std::uint8_t>(reply[i]);
  if (orch::traci::message_body_length(header, 1u << 30) != reply.size() - 4) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  orch::test::FakeEgoWorld world;
  world.vehicles["ego"] = {0, 0, 10, "E0", 1, 50, 4.5, {{"orch.hand_over", "0"}}};
  world.vehicles["actor1"] = {30, 0, 8, "E0", 1, 80, 4.6, {}};
  world.persons["actor2"] = {10, -3, 0, "E0", 0, 60, 0.3, {}};
  orch::traci::Session session(world, "fuzz");
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  std::size_t pos = 0;
  try {
    for (int messages = 0; input.size() - pos >= 4 && messages < 64; ++messages) {
      std::array<std::uint8_t, 4> header{};
      for (int i = 0; i < 4; ++i) header[i] = static_cast<std::uint8_t>(input[pos + i]);
      const std::size_t length = orch::traci::message_body_length(header);
      pos += 4;
      if (input.size() - pos < length) break;  // the plug-in went away mid-message
      auto next = session.handle(input.substr(pos, length));
      pos += length;
      for (int steps = 0; next == orch::traci::Session::Next::Step && steps < 1000; ++steps) {
        world.time = session.target();  // the world reached the target
        next = session.resume();
      }
      check_reply(session.take_reply());
      if (next == orch::traci::Session::Next::Close) break;
    }
  } catch (const orch::traci::DecodeError&) {
    // Malformed input: the server sends the error and closes. Expected.
  }
  return 0;
}
