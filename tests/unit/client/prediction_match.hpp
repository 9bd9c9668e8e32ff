// A match for the prediction tests: player 1 alone in level 1, playing, and the helpers
// that drive it (a snapshot as the server would send it, a thrust, the own ball).
#pragma once

#include <cstdint>

#include <catch2/catch.hpp>

#include "fts/protocol/snapshot.hpp"
#include "fts/room/snapshot_build.hpp"
#include "fts/sim/match.hpp"
#include "fts/sim/match_view.hpp"

namespace fts::client::test {

// One player in level 1 of a match with this configuration (no spawn protection),
// playing; the level's one enemy still at the centre.
inline sim::MatchState playing_alone(sim::MatchConfig cfg = {}) {
  cfg.spawn_protection_s = 0;
  auto s = sim::make_match(cfg, 3);
  sim::TickInputs join;
  join.joins.push_back({1, "ann"});
  sim::step(s, join);
  sim::TickInputs ready;
  sim::PlayerTick t;
  t.player = 1;
  t.commands.push_back({sim::CommandKind::ready, {}});
  ready.players.push_back(t);
  sim::step(s, ready);
  for (int i = 0; i < 400 && !(s.phase == sim::Phase::playing && s.players[0].ball); ++i) sim::step(s, {});
  REQUIRE(s.phase == sim::Phase::playing);
  REQUIRE(s.players[0].ball);
  return s;
}

// The snapshot the server would send of this state (quantized as on the wire).
inline protocol::Snapshot snapshot_of(const sim::MatchState& s) {
  return protocol::quantize(room::build_snapshot(sim::make_view(s), {}));
}

// Player 1 thrusting (dx, dy) this tick.
inline sim::TickInputs move(int dx, int dy) {
  sim::TickInputs in;
  sim::PlayerTick t;
  t.player = 1;
  t.input.move_x = static_cast<std::int8_t>(dx);
  t.input.move_y = static_cast<std::int8_t>(dy);
  in.players.push_back(t);
  return in;
}

inline const sim::Ball& own(const sim::MatchState& s) { return *sim::find_ball(s.world, s.players[0].ball); }

}  // namespace fts::client::test
