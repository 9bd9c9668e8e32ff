// The lean uplink (issue 14): hold_input sends a frame when the input changes (at most
// every 20 ms) and a keep-alive frame every 50 ms, each datagram with the newest 3 frames.
#include <catch2/catch.hpp>

#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

struct Uplink {
  std::uint64_t datagrams = 0, bytes = 0, frames_at_server = 0;
};

// One client holding `input_at(frame)` for 10 s, called every `frame_ms` (10: a bot's
// 100 Hz tick; 16: the terminal client's 60 fps frame); counts what went up.
template <class InputAt>
Uplink run(InputAt input_at, std::uint64_t frame_ms = 10) {
  Harness h;
  ClientConfig cc;
  cc.name = "lean";
  h.add_client(cc).client.connect(h.now);
  REQUIRE(h.run_until([&] { return h.peers[0]->client.state() == ClientState::connected; }, 5000));
  ClientEndpoint& c = h.peers[0]->client;
  h.server.take_inputs();
  const ClientStats before = c.stats();
  Uplink u;
  const std::uint64_t start = h.now;
  for (std::uint64_t t = 0; t * frame_ms < 10'000; ++t) {
    c.hold_input(input_at(t), start + frame_ms * t);
    h.step(start + frame_ms * t);
    u.frames_at_server += h.server.take_inputs().size();
  }
  const ClientStats after = c.stats();
  u.datagrams = after.datagrams_sent - before.datagrams_sent;
  u.bytes = after.bytes_sent - before.bytes_sent;
  return u;
}

}  // namespace

TEST_CASE("Lean uplink: a held input sends a keep-alive every 50 ms", "[protocol][uplink]") {
  const Uplink u = run([](std::uint64_t) { return InputFrame{0, 1, 0, false}; });
  CHECK(u.datagrams >= 195);  // 10 s at 20/s
  CHECK(u.datagrams <= 205);
  CHECK(u.frames_at_server == u.datagrams);  // each one a new frame: the input never expires
  CHECK(u.bytes / 10 <= 1500);
}

TEST_CASE("Lean uplink: steering every tick stays under 3 kB/s", "[protocol][uplink]") {
  // The worst case: the input changes at every tick (100 Hz).
  const Uplink u = run([](std::uint64_t t) {
    return InputFrame{0, static_cast<std::int8_t>(t % 3 - 1), static_cast<std::int8_t>(t / 3 % 3 - 1), false};
  });
  INFO("steering every tick: " << u.bytes / 10 << " B/s, " << u.datagrams / 10 << " datagrams/s");
  CHECK(u.datagrams <= 505);  // at most 50 a second
  // 3 kB/s of header and payload (issue 14), plus the 16-byte tag that seals each
  // datagram (issue 12, PROTOCOL.md 5.7): 800 B/s at 50 datagrams a second.
  CHECK(u.bytes / 10 - u.datagrams * kSealTagBytes / 10 <= 3000);
}

TEST_CASE("Lean uplink: the terminal client steering at every 60 fps frame stays under 3 kB/s",
          "[protocol][uplink]") {
  // fts-client passes its held input to hold_input once per drawn frame (--fps 60);
  // sealed datagrams, tags included.
  const Uplink u = run(
      [](std::uint64_t t) {
        return InputFrame{0, static_cast<std::int8_t>(t % 3 - 1), static_cast<std::int8_t>(t / 3 % 3 - 1), t % 7 == 0};
      },
      16);
  INFO("client at 60 fps, steering and firing: " << u.bytes / 10 << " B/s, " << u.datagrams / 10
                                                 << " datagrams/s");
  CHECK(u.datagrams <= 505);
  CHECK(u.bytes / 10 <= 3000);
}

TEST_CASE("Lean uplink: a fire between two sends is kept for the next one", "[protocol][uplink]") {
  Harness h;
  ClientConfig cc;
  cc.name = "fire";
  h.add_client(cc).client.connect(h.now);
  REQUIRE(h.run_until([&] { return h.peers[0]->client.state() == ClientState::connected; }, 5000));
  ClientEndpoint& c = h.peers[0]->client;
  const std::uint64_t t0 = h.now + 100;
  CHECK(c.hold_input({0, 1, 0, false}, t0) != 0);  // a change: sent
  CHECK(c.hold_input({0, 1, 0, true}, t0 + 10) == 0);  // too soon after the last send
  CHECK(c.hold_input({0, 1, 0, false}, t0 + 15) == 0);
  h.server.take_inputs();
  CHECK(c.hold_input({0, 1, 0, false}, t0 + 20) != 0);  // the kept fire goes out now
  h.step(t0 + 20);
  bool fired = false;
  for (const auto& in : h.server.take_inputs()) fired = fired || in.frame.fire;
  CHECK(fired);
}
