// GAME_RULES.md "Levels": n(L), enemy stats per kind, spawns, goal boxes.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "fts/sim/level.hpp"
#include "match_test_util.hpp"

using namespace fts::sim;

namespace {

// The rule exactly as written in GAME_RULES.md.
std::int64_t n_literal(std::int64_t L) {
  std::int64_t n = L;
  if (n > 7) n = 7 - L / 10;
  if (n < 5 && L > 5) n = 5;
  if (L % 10 == 0) {
    n = 1;
    if (L % 20 == 0) n = 2;
  }
  if (L % 10 == 5) n = 12;
  return n;
}

}  // namespace

TEST_CASE("Levels: enemy count n(L)") {
  const MatchConfig cfg;
  for (std::int64_t L = 1; L <= 200; ++L) {
    INFO("L = " << L);
    CHECK(enemy_count(L, cfg) == n_literal(L));
  }
  // Spot values.
  CHECK(enemy_count(1, cfg) == 1);
  CHECK(enemy_count(4, cfg) == 4);
  CHECK(enemy_count(5, cfg) == 12);
  CHECK(enemy_count(7, cfg) == 7);
  CHECK(enemy_count(9, cfg) == 7);
  CHECK(enemy_count(10, cfg) == 1);
  CHECK(enemy_count(11, cfg) == 6);
  CHECK(enemy_count(20, cfg) == 2);
  CHECK(enemy_count(21, cfg) == 5);
  CHECK(enemy_count(30, cfg) == 1);
  CHECK(enemy_count(31, cfg) == 5);
  CHECK(enemy_count(40, cfg) == 2);
}

TEST_CASE("Levels: enemy count scales with players, capped at 48") {
  const MatchConfig cfg;
  CHECK(enemy_count_for_players(3, 2, cfg) == 6);
  CHECK(enemy_count_for_players(5, 4, cfg) == 48);
  CHECK(enemy_count_for_players(5, 8, cfg) == 48);
  CHECK(enemy_count_for_players(10, 8, cfg) == 8);
  CHECK(enemy_count_for_players(20, 3, cfg) == 6);
  CHECK(enemy_count_for_players(7, 8, cfg) == 48);
}

TEST_CASE("Levels: enemy mass range, speeds and radii for L = 1..40") {
  const MatchConfig cfg;
  Rng rng(42);
  for (std::int64_t L = 1; L <= 40; ++L) {
    const std::int64_t q = L / 10;
    for (std::int64_t i = 0; i < enemy_count(L, cfg); ++i) {
      INFO("L = " << L << ", enemy " << i);
      const EnemySpec e = enemy_spec(L, i, rng, cfg);
      if (L == 1) {
        CHECK(e.mass == 30.0);
        CHECK(e.radius_u == 11.0 + 3.0);
        CHECK(e.role == EnemyRole::still);
        continue;
      }
      CHECK(e.role == (i == 3 ? EnemyRole::chaser : EnemyRole::wanderer));
      if (L % 10 == 0) {
        const double m = 100.0 * q - 100.0 * ((L - 10) / 20);
        CHECK(e.mass == m);
        CHECK(e.radius_u == 15.0 + std::floor(m / 8.0));
        CHECK(e.vmax_u_per_s == Approx((1.7 + 0.08 * q) * 100.0));
        CHECK(e.accel_u_per_s2 == Approx((0.01 + 0.0002 * q) * 1e4));
      } else if (L % 10 == 5) {
        CHECK(e.mass == 20.0 * (q + 1));
        CHECK(e.radius_u == 13.0 + std::floor(1.8 * q));
        CHECK(e.vmax_u_per_s == Approx((0.85 + 0.09 * L - 0.09 * q) * 100.0));
        CHECK(e.accel_u_per_s2 == Approx((0.0075 + 0.00065 * L - 0.0007 * q) * 1e4));
      } else {
        const double base = 28.0 + (21 * L) / 10 + 8.0 * q;
        CHECK(e.mass >= base - 4.0);
        CHECK(e.mass <= base + 4.0);
        CHECK(e.radius_u == 11.0 + std::floor(e.mass / 8.0));
        CHECK(e.vmax_u_per_s == Approx((1.1 + 0.11 * L - 0.1 * q) * 100.0));
        CHECK(e.accel_u_per_s2 == Approx((0.009 + 0.00065 * L - 0.0007 * q) * 1e4));
      }
    }
  }
}

TEST_CASE("Levels: normal mass jitter j = U(1..4) x U(-1..1) covers -4..4") {
  const MatchConfig cfg;
  Rng rng(7);
  std::set<double> seen;
  for (int i = 0; i < 2000; ++i) seen.insert(enemy_spec(3, 0, rng, cfg).mass - (28 + 6));
  CHECK(seen == std::set<double>{-4, -3, -2, -1, 0, 1, 2, 3, 4});
}

TEST_CASE("Levels: spawns in the inner box, never overlapping, level 1's enemy at the centre") {
  using namespace fts::test;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    MatchState s = started(4, seed);
    step(s, {});
    // Jump to level 7 with 4 players: 28 enemies.
    remove_enemies(s);
    std::vector<Event> ev;
    const auto extra = add_enemy(s, {250, 150});
    (void)extra;
    s.phase = Phase::shop;
    s.level = 6;
    s.shop_deadline_tick = s.tick;
    ev = step(s, {}).events;
    REQUIRE(s.level == 7);
    std::int64_t enemies = 0;
    for (const Ball& b : s.world.balls) {
      if (s.bodies[b.id].kind != BodyKind::enemy) continue;
      ++enemies;
      // Spawned inside [50, 450] x [50, 250] (one tick of motion allowed).
      CHECK(b.pos.x >= 45.0);
      CHECK(b.pos.x <= 455.0);
      CHECK(b.pos.y >= 45.0);
      CHECK(b.pos.y <= 255.0);
    }
    CHECK(enemies == 28);
    CHECK(max_penetration(s.world.balls) == 0.0);
  }
  MatchState s = started(1, 3);
  REQUIRE(s.world.balls.size() == 2);
  const Ball* enemy = nullptr;
  for (const Ball& b : s.world.balls)
    if (s.bodies[b.id].kind == BodyKind::enemy) enemy = &b;
  REQUIRE(enemy);
  CHECK(enemy->pos == Vec2{250, 150});
  CHECK(enemy->mass == 30.0);
  // It does not move by itself.
  fts::test::run(s, 300);
  CHECK(find_ball(s.world, enemy->id)->pos == Vec2{250, 150});
}

TEST_CASE("Levels: players start along the left third, vertical centre for one") {
  using namespace fts::test;
  MatchState one = started(1);
  CHECK(ball_of(one, 1).pos.x == Approx(500.0 / 6.0));
  CHECK(ball_of(one, 1).pos.y == 150.0);
  MatchState three = started(3);
  CHECK(ball_of(three, 1).pos.y == 75.0);
  CHECK(ball_of(three, 2).pos.y == 150.0);
  CHECK(ball_of(three, 3).pos.y == 225.0);
  for (std::uint32_t p = 1; p <= 3; ++p) CHECK(ball_of(three, p).pos.x < 500.0 / 3.0);
}

TEST_CASE("Levels: wander goals lie in the shrinking box, bosses in 90 x 45") {
  const MatchConfig cfg;
  CHECK(goal_half_size(2, cfg) == Vec2{146, 96});
  CHECK(goal_half_size(29, cfg) == Vec2{92, 42});
  CHECK(goal_half_size(45, cfg) == Vec2{90, 40});
  CHECK(goal_half_size(10, cfg) == Vec2{90, 45});
  CHECK(goal_half_size(40, cfg) == Vec2{90, 45});
  Rng rng(1);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 g = draw_goal(12, rng, cfg);
    CHECK(std::fabs(g.x - 250) <= 150 - 24);
    CHECK(std::fabs(g.y - 150) <= 100 - 24);
  }
}

TEST_CASE("Levels: the fourth enemy chases the nearest living player") {
  using namespace fts::test;
  MatchState s = started(1, 5);
  // Go to level 4 (4 enemies, index 3 chases).
  s.phase = Phase::shop;
  s.level = 3;
  s.shop_deadline_tick = s.tick;
  step(s, {});
  REQUIRE(s.level == 4);
  BallId chaser = 0;
  for (const auto& [id, b] : s.bodies)
    if (b.kind == BodyKind::enemy && b.spec.role == EnemyRole::chaser) chaser = id;
  REQUIRE(chaser != 0);
  const double d0 = length(find_ball(s.world, chaser)->pos - ball_of(s, 1).pos);
  run(s, 100);
  REQUIRE(find_ball(s.world, chaser));
  CHECK(s.bodies[chaser].goal == ball_of(s, 1).pos);
  CHECK(length(find_ball(s.world, chaser)->pos - ball_of(s, 1).pos) < d0);
}
