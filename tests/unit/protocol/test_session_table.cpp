// The endpoint's table of sessions (server_session.hpp, issue 39): lookups by address and
// session id follow index and unindex, a session leaving takes only its own index entries,
// and player ids skip the ids rooms from elsewhere took.
#include <catch2/catch.hpp>

#include "fts/protocol/server_session.hpp"

using fts::protocol::ServerSession;
using fts::protocol::SessionTable;

namespace {

ServerSession& add(SessionTable& t, std::uint32_t player, std::uint32_t session_id, const std::string& address) {
  ServerSession& s = t[player];
  s.player_id = player;
  s.session_id = session_id;
  s.address = address;
  t.index(s);
  return s;
}

}  // namespace

TEST_CASE("Session table: lookups by address and session id follow the indexes", "[protocol][sessions]") {
  SessionTable t;
  ServerSession& ann = add(t, 5, 1001, "10.0.0.1:4000");
  add(t, 6, 1002, "10.0.0.2:4000");
  REQUIRE(t.at_address("10.0.0.1:4000") == &ann);
  REQUIRE(t.with_session_id(1001) == &ann);
  CHECK(t.session_id_taken(1002));
  CHECK(t.at_address("10.0.0.9:4000") == nullptr);
  CHECK(t.with_session_id(7) == nullptr);

  // Ann's client comes back from bob's old address after bob moved on to another: ann's
  // entry is the address's now, and bob leaving does not take it from her.
  ServerSession& bob = t.at(6);
  t.unindex(ann);
  ann.address = "10.0.0.2:4000";
  t.index(ann);
  t.unindex(bob);  // bob still names 10.0.0.2:4000
  CHECK(t.at_address("10.0.0.2:4000") == &ann);
  CHECK(t.with_session_id(1002) == nullptr);
  CHECK(t.at_address("10.0.0.1:4000") == nullptr);

  // Erasing a session drops its entries; the others stay.
  t.erase(t.find(5));
  CHECK(t.count(5) == 0);
  CHECK(t.at_address("10.0.0.2:4000") == nullptr);
  CHECK(t.with_session_id(1001) == nullptr);
  CHECK(t.size() == 1);
}

TEST_CASE("Session table: player ids count on past reserved and taken ids", "[protocol][sessions][ids]") {
  SessionTable t(100);
  CHECK(t.next_player_id() == 100);
  t.take_player_id(101);  // a room from another server names player 101
  t.take_player_id(103);
  t.reserve_player_ids(100);
  CHECK(t.next_player_id() == 102);  // 101 skipped, not given
  t.reserve_player_ids(102);
  CHECK(t.next_player_id() == 104);
  t.take_player_id(50);  // below the next id: nothing to keep out
  t.reserve_player_ids(SessionTable::kNoPlayerIdLeft - 1);
  CHECK(t.next_player_id() == SessionTable::kNoPlayerIdLeft);  // none left
  CHECK(SessionTable(0).next_player_id() == 1);  // 0 is no player id
}
