// Sessions carried over a server restart (issue 15): the journal keeps a verifier of each
// token, never the token; the restarted server (a new key) takes the player back when
// its client comes with the old token.
#include <catch2/catch.hpp>

#include "fts/protocol/cookie.hpp"
#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

ServerConfig other_key_config() {
  ServerConfig c = test_server_config();
  c.key[0] ^= 0xff;
  return c;
}

}  // namespace

TEST_CASE("Restore: a restarted server takes a player back by its old token", "[protocol][sessions][restore]") {
  Harness before;
  Peer& p = before.add_client(named("ann"));
  p.client.connect(before.now);
  REQUIRE(before.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
  const std::uint32_t id = p.client.welcome()->player_id;
  const std::string token = p.client.welcome()->token;
  const std::string verifier = before.server.session_verifier(id);
  CHECK(verifier == token_verifier(token));
  CHECK(verifier != token);
  CHECK(verifier.size() == 32);
  CHECK(before.server.session_verifier(99).empty());

  Harness after(other_key_config());
  after.now = 5;  // a new process: its clock starts again
  REQUIRE(after.server.restore_session({id, "ann", verifier, false}, after.now));
  const auto events = after.server.take_events();
  REQUIRE(events.size() == 1);
  CHECK(events[0].kind == ServerEvent::Kind::disconnected);
  CHECK(events[0].player_id == id);
  CHECK(events[0].reason == "restart");
  REQUIRE(after.server.sessions().size() == 1);
  CHECK_FALSE(after.server.sessions()[0].connected);

  // A wrong token is refused; the right one is a reconnect to the same player.
  Peer& wrong = after.add_client(named("eve", std::string(32, '0')));
  wrong.client.connect(after.now);
  REQUIRE(after.run_until([&] { return wrong.client.state() == ClientState::refused; }, 1000));
  CHECK(wrong.client.error()->code == "bad_token");
  Peer& back = after.add_client(named("ann", token));
  back.client.connect(after.now);
  REQUIRE(after.run_until([&] { return back.client.state() == ClientState::connected; }, after.now + 1000));
  CHECK(back.client.welcome()->player_id == id);
  CHECK(back.client.welcome()->reconnected);
  CHECK(back.client.welcome()->token == token);
  const auto again = after.server.take_events();
  REQUIRE(again.size() == 1);
  CHECK(again[0].kind == ServerEvent::Kind::reconnected);
  CHECK(after.server.session_verifier(id) == verifier);
}

TEST_CASE("Restore: a bad restored session is refused and changes nothing", "[protocol][sessions][restore]") {
  Harness h;
  const std::string v = token_verifier("00112233445566778899aabbccddeeff");
  CHECK_FALSE(h.server.restore_session({0, "ann", v, false}, h.now));
  CHECK_FALSE(h.server.restore_session({1, "ann", "not-hex", false}, h.now));
  CHECK_FALSE(h.server.restore_session({1, "ann", v.substr(1), false}, h.now));
  CHECK_FALSE(h.server.restore_session({1, "", v, false}, h.now));
  CHECK(h.server.sessions().empty());
  CHECK(h.server.take_events().empty());
  CHECK(h.server.restore_session({1, "ann", v, false}, h.now));
  CHECK_FALSE(h.server.restore_session({1, "bob", v, false}, h.now));
  CHECK(h.server.sessions().size() == 1);
}

TEST_CASE("Restore: a restored player nobody comes back for is released after the window",
          "[protocol][sessions][restore]") {
  ServerConfig c = test_server_config();
  c.reconnect_window_ms = 2000;
  Harness h(c);
  REQUIRE(h.server.restore_session({3, "ann", token_verifier("x"), false}, h.now));
  h.server.take_events();
  h.run_until([] { return false; }, h.now + 1900);
  CHECK(h.server.take_events().empty());
  h.run_until([] { return false; }, h.now + 200);
  const auto events = h.server.take_events();
  REQUIRE(events.size() == 1);
  CHECK(events[0].kind == ServerEvent::Kind::released);
  CHECK(h.server.sessions().empty());
}

TEST_CASE("Restore: a session restored after a long pause of the endpoint is held for the window",
          "[protocol][sessions][restore]") {
  Harness h;
  h.server.update(100);
  (void)h.server.take_events();
  // The loop was busy for 5 s (a stall), then restores a room's session (a hand-over).
  const std::string v = token_verifier(std::string(32, 'a'));
  REQUIRE(h.server.restore_session({7, "ann", v, false}, 5100, 1, "ROOMA"));
  h.server.set_keeps_departed(1, true);
  for (std::uint64_t t = 5105; t < 5200; t += 5) h.server.update(t);
  const auto events = h.server.take_events();
  REQUIRE(events.size() == 1);  // the restore's own "restart", nothing after it
  CHECK(events[0].reason == "restart");
  REQUIRE(h.server.sessions().size() == 1);
  CHECK(h.server.sessions()[0].player_id == 7);
}
