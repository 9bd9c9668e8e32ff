// Issue 26, point 2: the snapshot a client reads carries a player's spawn protection, in
// both encodings, in a full snapshot and in a delta (when it ends).
#include <catch2/catch.hpp>

#include "../match/match_test_util.hpp"
#include "fts/room/snapshot_build.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/snapshot_delta.hpp"
#include "fts/sim/match_view.hpp"

using namespace fts;
using namespace fts::test;

namespace {

// The snapshot as a client reconstructs it after the wire (against `base`, if any).
protocol::Snapshot through_wire(const protocol::Snapshot& now, const protocol::Snapshot* base,
                                protocol::Encoding encoding) {
  const protocol::SnapshotMsg msg = protocol::make_snapshot_msg(now, base, 100);
  const auto bytes = protocol::encode_payload(encoding, {msg});
  auto decoded = protocol::decode_payload(encoding, bytes);
  REQUIRE(decoded.ok());
  REQUIRE(decoded->size() == 1);
  auto snap = protocol::apply_snapshot({std::get<protocol::SnapshotMsg>((*decoded)[0])}, base);
  REQUIRE(snap.ok());
  return *snap;
}

}  // namespace

TEST_CASE("Snapshot: a player entry carries spawn protection until its tick", "[snapshot][protection]") {
  MatchState s = started(2);
  remove_enemies(s);
  add_enemy(s, {440, 280});
  // As if both had acted since the level start (which protects everyone, issue 37):
  // player 1's protection below is its respawn's, player 2 has none.
  for (Player& p : s.players) p.protected_until_tick = -1;
  ball_of(s, 1).pos = {-1, 100};
  for (int i = 0; i < 400 && find_player(s, 1)->protected_until_tick < 0; ++i) step(s, {});
  const std::int64_t until = find_player(s, 1)->protected_until_tick;
  REQUIRE(until > s.tick);

  for (const auto encoding : {protocol::Encoding::json, protocol::Encoding::msgpack}) {
    const protocol::Snapshot full = room::build_snapshot(make_view(s), {});
    const protocol::Snapshot got = through_wire(full, nullptr, encoding);
    REQUIRE(got.players.size() == 2);
    CHECK(got.players[0].protected_until_tick == static_cast<std::uint32_t>(until));
    CHECK(got.players[1].protected_until_tick == 0);

    MatchState later = s;
    TickInputs thrust;
    thrust.players.push_back({1, {1, 0, false}, {}});
    step(later, thrust);  // acting ends it
    const protocol::Snapshot delta = through_wire(room::build_snapshot(make_view(later), {}), &got, encoding);
    CHECK(delta.players[0].protected_until_tick == 0);
  }
}
