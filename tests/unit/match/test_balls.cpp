// GAME_RULES.md "Balls" and "The platform" inside a match: radius from mass, friction and
// its cut-off, thrust with the per-axis vmax clamp, falling off an open edge.
#include <catch2/catch.hpp>

#include <cmath>

#include "match_test_util.hpp"

using namespace fts::sim;
using namespace fts::test;

namespace {

MatchState bare_one() {
  MatchState s = started(1);
  remove_enemies(s);
  add_enemy(s, {450, 30});
  return s;
}

}  // namespace

TEST_CASE("Balls: radius from mass r = 11 + floor(mass / 8)") {
  const MatchConfig cfg;
  CHECK(radius_for_mass(cfg, 40) == 16);
  CHECK(radius_for_mass(cfg, 30) == 14);
  CHECK(radius_for_mass(cfg, 47) == 16);
  CHECK(radius_for_mass(cfg, 48) == 17);
  MatchState s = started(1);
  CHECK(ball_of(s, 1).radius == 16);
  CHECK(ball_of(s, 1).mass == 40);
}

TEST_CASE("Balls: friction 0.991 per frame - a slower component stops") {
  MatchState s = bare_one();
  const BallId e = add_enemy(s, {250, 150}, {100, 0.5});
  step(s, {});
  const Ball* b = find_ball(s.world, e);
  CHECK(b->vel.x == Approx(99.1));
  CHECK(b->vel.y == 0.0);
  run(s, 99);
  CHECK(find_ball(s.world, e)->vel.x == Approx(100 * std::pow(0.991, 100)).epsilon(1e-9));
}

TEST_CASE("Balls: friction is per configured frame (frame_s), not per 0.01 s") {
  MatchConfig cfg;
  cfg.frame_s = 0.02;  // a 50 fps original: half the decay per second
  MatchState s = started(1, 1, cfg);
  remove_enemies(s);
  add_enemy(s, {450, 30});
  const BallId e = add_enemy(s, {250, 150}, {100, 0});
  run(s, 100);  // one second at 100 Hz
  CHECK(find_ball(s.world, e)->vel.x == Approx(100 * std::pow(0.991, 50)).epsilon(1e-9));
}

TEST_CASE("Balls: thrust 200 u/s^2 up to vmax 170 u/s on each axis separately") {
  MatchState s = bare_one();
  TickInputs in;
  in.players.push_back({1, {1, 1, false}, {}});
  step(s, in);
  CHECK(ball_of(s, 1).vel.x == Approx(2.0 * 0.991));
  run(s, 59, in);
  CHECK(ball_of(s, 1).vel.y == ball_of(s, 1).vel.x);  // diagonal: both axes alike
  CHECK(ball_of(s, 1).vel.x < 170.0);                  // still accelerating after 0.6 s
  // Along x from the left edge: the clamp holds the component near 170 u/s.
  ball_of(s, 1).pos = {20, 150};
  ball_of(s, 1).vel = {};
  TickInputs right;
  right.players.push_back({1, {1, 0, false}, {}});
  for (int i = 0; i < 200; ++i) {
    step(s, right);
    CHECK(ball_of(s, 1).vel.x <= 172.0);
  }
  CHECK(ball_of(s, 1).vel.x >= 165.0);
  CHECK(ball_of(s, 1).vel.y == 0.0);
}

TEST_CASE("Balls: no thrust on an axis whose speed is at or above vmax, even to brake") {
  // The original clamps each component: thrust applies only while |v| < vmax.
  MatchState a = bare_one(), b = bare_one();
  ball_of(a, 1).vel = {400, 0};
  ball_of(b, 1).vel = {400, 0};
  TickInputs brake;
  brake.players.push_back({1, {-1, 0, false}, {}});
  run(a, 20, brake);
  run(b, 20);
  CHECK(ball_of(a, 1).vel.x == ball_of(b, 1).vel.x);  // friction alone slowed both
  // Below vmax, thrust against the motion brakes.
  MatchState c = bare_one(), d = bare_one();
  ball_of(c, 1).vel = {100, 0};
  ball_of(d, 1).vel = {100, 0};
  run(c, 20, brake);
  run(d, 20);
  CHECK(ball_of(c, 1).vel.x < ball_of(d, 1).vel.x - 30.0);
}

TEST_CASE("The platform: a ball whose centre leaves the rectangle has fallen off") {
  MatchState s = bare_one();
  const BallId inside = add_enemy(s, {499.5, 150}, {10, 0});   // centre stays inside this tick
  const BallId outside = add_enemy(s, {499.5, 200}, {100, 0}); // centre crosses x = 500
  const auto ev = step(s, {}).events;
  CHECK(find_ball(s.world, inside));
  CHECK_FALSE(find_ball(s.world, outside));
  REQUIRE(of<EnemyDefeated>(ev).size() == 1);
  CHECK(of<EnemyDefeated>(ev)[0].enemy == outside);
}
