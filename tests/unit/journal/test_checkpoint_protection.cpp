// Issue 26, point 2 and issue 37, point 2: spawn protection is part of the checkpoint.
// Written and read back, a match restored in the middle of a blow on a protected ball
// steps on bit for bit; a checkpoint written before the field existed reads as
// unprotected. (The match-level cases are in unit/match/test_spawn_protection.cpp; this
// one needs the host's checkpoint codec, so it lives with the journal's tests.)
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "../match/match_test_util.hpp"
#include "store/match_state_json.hpp"

using namespace fts;
using namespace fts::test;

TEST_CASE("Checkpoint: spawn protection is kept, and a restored blow steps on bit for bit",
          "[journal][protection]") {
  // Two players at the start of level 1: both protected from the level start. The level's
  // enemy is replaced by a still one far off, and a heavy fast one (mass 200, 400 u/s)
  // comes at player 1's ball from the right.
  MatchState s = started(2, 1);
  const std::int64_t until = find_player(s, 1)->protected_until_tick;
  REQUIRE(until > s.tick);
  remove_enemies(s);
  add_enemy(s, {440, 280});
  const Vec2 at = ball_of(s, 1).pos;
  add_enemy(s, {at.x + 80, at.y}, {-400, 0}, 200.0);
  run(s, 5);

  const auto j = store::match_state_to_json(s);
  CHECK(j.dump().find("null") == std::string::npos);  // no infinite mass was written
  CHECK(j["players"][0]["protected_until_tick"] == until);
  auto back = store::match_state_from_json(nlohmann::json::parse(j.dump()), make_match(s.cfg, 99));
  REQUIRE(std::holds_alternative<MatchState>(back));
  MatchState b = std::get<MatchState>(back);
  CHECK(b.players[0].protected_until_tick == until);
  CHECK(match_hash(b) == match_hash(s));
  for (int i = 0; i < 400; ++i) {
    step(s, {});
    step(b, {});
    REQUIRE(match_hash(b) == match_hash(s));
  }
  CHECK(s.tick > until);
  CHECK(b.players[0].protected_until_tick == -1);

  auto old = j;
  old["players"][0].erase("protected_until_tick");
  auto read_old = store::match_state_from_json(old, make_match(s.cfg, 99));
  REQUIRE(std::holds_alternative<MatchState>(read_old));
  CHECK(std::get<MatchState>(read_old).players[0].protected_until_tick == -1);
}
