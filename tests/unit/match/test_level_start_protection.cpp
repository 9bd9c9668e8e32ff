// Issue 37, point 2: every player is protected at every level start (a restart
// included), not only at a respawn. An idle ball was knocked off 4 s into level 4, and
// a player on a 150 ms link lost all three lives while idle. Time is stepped by hand.
#include <catch2/catch.hpp>

#include "match_test_util.hpp"

using namespace fts;
using namespace fts::test;

namespace {

// The tick of the first LevelStarted in `ev` (-1: none).
std::int64_t level_start_tick(MatchState& s, int max_ticks, bool& restart) {
  for (int i = 0; i < max_ticks; ++i) {
    const std::int64_t t = s.tick;
    for (const Event& e : step(s, {}).events)
      if (const auto* x = std::get_if<LevelStarted>(&e)) {
        restart = x->restart;
        return t;
      }
  }
  return -1;
}

// A heavy, fast enemy (mass 200 at 400 u/s) at player p's ball from the right; the
// level's own enemies replaced by a still one far off, so that the level stays open.
void blow(MatchState& s, PlayerId p) {
  remove_enemies(s);
  add_enemy(s, {440, 280});
  const Vec2 at = ball_of(s, p).pos;
  add_enemy(s, {at.x + 80, at.y}, {-400, 0}, 200.0);
}

// Player p's ball stays where the level put it, however hard it is hit, until its
// protection ends; then the same blow knocks it off.
void holds_then_falls(MatchState& s, PlayerId p, std::int64_t start_tick) {
  const std::int64_t until = start_tick + 300;  // 3 s at 100 Hz
  REQUIRE(find_player(s, p)->protected_until_tick == until);
  const Vec2 at = ball_of(s, p).pos;
  blow(s, p);
  std::vector<Event> ev;
  while (s.tick < until) {
    auto out = step(s, {}).events;
    ev.insert(ev.end(), out.begin(), out.end());
    REQUIRE(find_player(s, p)->ball != 0);
    CHECK(ball_of(s, p).pos == at);
  }
  CHECK_FALSE(fell(ev, p));
  step(s, {});
  CHECK(find_player(s, p)->protected_until_tick == -1);
  blow(s, p);
  CHECK(fell(run(s, 100), p));
}

}  // namespace

TEST_CASE("Level start protection: idle players at the first level's start cannot be pushed off",
          "[match][protection]") {
  for (const Model model : {Model::continuous, Model::discrete, Model::seed}) {
    INFO(to_string(model));
    MatchConfig cfg;
    cfg.model = model;
    MatchState s = make_match(cfg, 1);
    step(s, joins(2));
    const std::int64_t t = s.tick;
    bool started = false;
    for (const Event& e : step(s, all_ready(s)).events) started = started || std::holds_alternative<LevelStarted>(e);
    REQUIRE(started);
    CHECK(find_player(s, 2)->protected_until_tick == t + 300);  // both of them
    holds_then_falls(s, 1, t);
  }
}

TEST_CASE("Level start protection: a level restart protects every player again", "[match][protection]") {
  MatchState s = started(1);
  // The only player falls: nobody is left on the platform and the level restarts.
  ball_of(s, 1).pos = {-1, 100};
  bool restart = false;
  const std::int64_t t = level_start_tick(s, 50, restart);
  REQUIRE(t >= 0);
  REQUIRE(restart);
  REQUIRE(find_player(s, 1)->ball != 0);
  holds_then_falls(s, 1, t);
}

TEST_CASE("Level start protection: the next level after the shop protects every player", "[match][protection]") {
  MatchState s = started(2);
  remove_enemies(s);  // level 1 cleared
  step(s, {});
  REQUIRE(s.phase == Phase::shop);
  std::int64_t t = s.tick;
  bool started = false;
  for (const Event& e : step(s, all_ready(s)).events) started = started || std::holds_alternative<LevelStarted>(e);
  bool restart = true;
  if (!started) t = level_start_tick(s, 3000, restart);
  REQUIRE(s.phase == Phase::playing);
  REQUIRE(s.level == 2);
  CHECK(find_player(s, 1)->protected_until_tick == t + 300);
  holds_then_falls(s, 2, t);
}

TEST_CASE("Level start protection: none when spawn protection is off (0 s)", "[match][protection]") {
  MatchConfig cfg;
  cfg.spawn_protection_s = 0.0;
  MatchState s = started(2, 1, cfg);
  CHECK(find_player(s, 1)->protected_until_tick == -1);
  blow(s, 1);
  CHECK(fell(run(s, 100), 1));
}
