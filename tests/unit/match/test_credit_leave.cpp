// A credit dies with its player (issue 36 point 10): when a player leaves the match, no
// enemy's credit names it and its rockets go, so a later player with that id (a server
// that reused ids did that) is credited for nothing the leaver did.
#include <catch2/catch.hpp>

#include "match_test_util.hpp"

using namespace fts::sim;
using namespace fts::test;

namespace {

TickInputs leave(PlayerId p) {
  TickInputs in;
  in.leaves.push_back(p);
  return in;
}

}  // namespace

TEST_CASE("Credit: an enemy touched by a player who left credits nobody, not a newcomer with its id") {
  MatchState s = started(2);
  remove_enemies(s);
  add_enemy(s, {60, 30});  // an anchor: the level goes on
  const BallId e = add_enemy(s, {440, 150}, {300, 0});  // heads for the edge
  s.bodies[e].credit = 1;
  s.bodies[e].credit_tick = s.tick;
  step(s, leave(1));
  CHECK(s.bodies.at(e).credit == PlayerId{0});
  // A newcomer with the leaver's id (what an id-reusing server gave the next session).
  TickInputs in;
  in.joins.push_back({1, "new"});
  step(s, in);
  REQUIRE(find_player(s, 1));
  const auto ev = run(s, 200);
  const EnemyDefeated* d = defeat_of(ev, e);
  REQUIRE(d);
  CHECK(d->player == PlayerId{0});
  CHECK(d->coins == 0);
  CHECK(find_player(s, 1)->eco.coins == 0);
}

TEST_CASE("Credit: a player's rockets leave with it - other players' credit stays") {
  MatchState s = started(2);
  remove_enemies(s);
  const BallId e1 = add_enemy(s, {60, 30});
  const BallId e2 = add_enemy(s, {60, 200});
  s.bodies[e1].credit = 1;
  s.bodies[e2].credit = 2;
  s.bodies[e1].credit_tick = s.bodies[e2].credit_tick = s.tick;
  const BallId rocket = add_enemy(s, {250, 250}, {}, 1.0);  // made a rocket of player 1 by hand
  s.bodies[rocket].kind = BodyKind::rocket;
  s.bodies[rocket].owner = 1;
  s.bodies[rocket].expires_tick = s.tick + 1000;
  step(s, leave(1));
  CHECK(s.bodies.count(rocket) == 0);
  CHECK(find_ball(s.world, rocket) == nullptr);
  CHECK(s.bodies.at(e1).credit == PlayerId{0});
  CHECK(s.bodies.at(e1).credit_tick == -1);
  CHECK(s.bodies.at(e2).credit == PlayerId{2});
}
