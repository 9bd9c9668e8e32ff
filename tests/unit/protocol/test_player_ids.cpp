// Player ids are never reused in an endpoint's life (issue 36 point 10): not a released
// session's, not one below a restored session's, and past the last one nobody new is
// taken. (A new session took the lowest free id, so a newcomer inherited a departed
// player's credit.) Time stepped by hand.
#include <catch2/catch.hpp>

#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

std::uint32_t join(Harness& h, const std::string& name) {
  Peer& p = h.add_client(named(name));
  p.client.connect(h.now);
  const bool done = h.run_until([&] { return p.client.state() != ClientState::connecting; }, h.now + 1000);
  return done && p.client.welcome() ? p.client.welcome()->player_id : 0;
}

}  // namespace

TEST_CASE("Player ids: never reused, above every restored id, none past the last", "[protocol][sessions][ids]") {
  Harness h;
  // A restored session (a resumed room's player 7): a newcomer's id is above it.
  REQUIRE(h.server.restore_session({7, "ann", std::string(32, 'a'), false}, h.now));
  const std::uint32_t bob = join(h, "bob");
  CHECK(bob == 8);  // was 1, the lowest free
  CHECK_FALSE(h.server.restore_session({7, "ann", std::string(32, 'a'), false}, h.now));  // 7 is in use
  // A released session's id is not given again.
  h.server.kick(bob, ErrorCode::kicked, "test", h.now);
  CHECK(join(h, "cy") == 9);
  // Ids only go up; the last one is given, then every new player is refused.
  h.server.reserve_player_ids(3);
  h.server.reserve_player_ids(ServerEndpoint::kNoPlayerIdLeft - 2);
  CHECK(join(h, "dan") == ServerEndpoint::kNoPlayerIdLeft - 1);
  Peer& eve = h.add_client(named("eve"));
  eve.client.connect(h.now);
  REQUIRE(h.run_until([&] { return eve.client.state() == ClientState::refused; }, h.now + 1000));
  CHECK(eve.client.error()->code == "server_full");
  CHECK(h.server.sessions().size() == 3);
}

// A room handed over by another server (issue 42) names that server's ids: taken here, one
// by one, without moving this endpoint's own ids into that server's range (where its next
// room would find them in use).
TEST_CASE("Player ids: a fleet server's own range, and a room's ids from elsewhere taken one by one",
          "[protocol][sessions][ids]") {
  ServerConfig config = test_server_config();
  config.first_player_id = 5000;
  Harness h(config);
  CHECK(join(h, "ann") == 5000);
  // A foreign room's session (another server's 9000) and one of its departed players
  // (5002) are taken: the newcomers go on at 5001, skip 5002, and never reach 9001.
  REQUIRE(h.server.restore_session({9000, "bob", std::string(32, 'b'), false, "", true}, h.now));
  h.server.take_player_id(5002);
  CHECK(join(h, "cy") == 5001);
  CHECK(join(h, "dan") == 5003);
  CHECK(join(h, "eve") == 5004);
  // The same ids restored as this server's own (a --resume) do move its ids on.
  Harness own;
  REQUIRE(own.server.restore_session({9000, "bob", std::string(32, 'b'), false}, own.now));
  CHECK(join(own, "fay") == 9001);
}
