// A session replaced by a new client on its address (a new hello, a new nonce, no token:
// PROTOCOL.md 5.3) is ended; one that never played holds no slot (6): it is freed at
// once and its token is then unknown (regression, issue 36: it stayed listed, away, and
// its token still took it back). One that played is held for the reconnect window.
// Time is stepped by hand over in-memory links.
#include <catch2/catch.hpp>

#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {


std::size_t released(const std::vector<ServerEvent>& events, std::uint32_t player, const std::string& reason) {
  std::size_t n = 0;
  for (const auto& e : events) n += e.kind == ServerEvent::Kind::released && e.player_id == player && e.reason == reason;
  return n;
}

}  // namespace

TEST_CASE("Replaced session: one that never played is freed at once, its token dead", "[protocol][slots][replaced]") {
  const bool played = GENERATE(false, true);
  INFO((played ? "the first session played" : "the first session never played"));
  Harness h;
  const std::string address = "10.0.0.9:5000";
  Peer& first = h.add_client(named("ann"), {}, address);
  first.client.connect(h.now);
  REQUIRE(h.run_until([&] { return connected(first); }, 1000));
  if (played) first.client.send_input({0, 1, 0, false}, h.now);  // a key down: real input
  h.run_until([&] { return false; }, h.now + 200);
  const std::string token = first.client.welcome()->token;
  const std::uint32_t player = first.client.welcome()->player_id;
  h.server.take_events();

  // The process dies without a bye; a new one (a new nonce, no token) starts on the address.
  first.up = LossyLink({1.0, 0, 0, 0, 1});
  first.down = LossyLink({1.0, 0, 0, 0, 2});
  Peer& second = h.add_client(named("bob"), {}, address);
  second.client.connect(h.now);
  REQUIRE(h.run_until([&] { return connected(second); }, h.now + 1000));
  const auto events = h.server.take_events();
  CHECK(released(events, player, "replaced") == (played ? 0u : 1u));
  CHECK(h.server.sessions().size() == (played ? 2u : 1u));

  // The first session's token from elsewhere: taken back only if it played.
  Peer& back = h.add_client(named("ann", token), {}, "10.0.0.10:5000");
  back.client.connect(h.now);
  REQUIRE(h.run_until([&] { return back.client.state() == ClientState::connected ||
                                   back.client.state() == ClientState::refused; },
                      h.now + 2000));
  if (played) {
    REQUIRE(connected(back));
    CHECK(back.client.welcome()->reconnected);
    CHECK(back.client.welcome()->player_id == player);
  } else {
    REQUIRE(back.client.state() == ClientState::refused);
    REQUIRE(back.client.error());
    CHECK(back.client.error()->code == "bad_token");
  }
}
