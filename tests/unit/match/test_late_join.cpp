// Issue 26, point 2: a player who joins a running match starts with the automatic growth
// of every level cleared (multiplier x1.02, life price x1.015 each) and the median of the
// total values (coins + spent) of the players still in the match; nobody loses anything,
// and a player coming back with its token is no newcomer.
#include <catch2/catch.hpp>

#include "match_test_util.hpp"

using namespace fts;
using namespace fts::test;

namespace {

// Three players at the start of level 8 (levels 1-7 cleared by taking their enemies off),
// with total values 1000 (all in hand), 3000 (2800 of it spent) and 200.
MatchState at_level_8(MatchConfig cfg = {}) {
  MatchState s = started(3, 1, cfg);
  while (s.level < 8) {
    remove_enemies(s);
    step(s, {});  // level complete: the shop
    REQUIRE(s.phase == Phase::shop);
    step(s, all_ready(s));
  }
  REQUIRE(s.phase == Phase::playing);
  REQUIRE(s.levels_cleared == 7);
  find_player(s, 1)->eco.coins = 1000;
  find_player(s, 2)->eco.coins = 200;
  find_player(s, 2)->eco.spent = 2800;
  find_player(s, 3)->eco.coins = 200;
  return s;
}

TickInputs join(PlayerId id) {
  TickInputs in;
  in.joins.push_back({id, "late"});
  return in;
}

}  // namespace

TEST_CASE("Late join: at level 8 the newcomer gets the median total value and the levels' growth",
          "[match][late_join]") {
  MatchState s = at_level_8();
  const std::vector<Player> before = s.players;
  step(s, join(4));
  const Player* p = find_player(s, 4);
  REQUIRE(p);
  CHECK(p->eco.coins == 1000);  // the median of 1000, 3000 and 200
  CHECK(p->eco.start_coins == 1000);
  CHECK(p->eco.spent == 0);
  CHECK(p->eco.earned_defeats == 0);
  CHECK(p->eco.multiplier == Approx(1.148685667));  // 1.02^7, as the others got it
  CHECK(p->eco.multiplier == find_player(s, 1)->eco.multiplier);
  CHECK(price_of(p->eco, Item::life) == price_of(find_player(s, 1)->eco, Item::life));  // 500 x 1.015^7
  CHECK(price_of(p->eco, Item::life) == 554);
  // The rest is the original start: mass, speeds, lives, prices of the upgrades.
  const Economy start = start_economy(s.cfg);
  CHECK(p->eco.lives == start.lives);
  CHECK(p->eco.mass == start.mass);
  CHECK(p->eco.vmax_u_per_s == start.vmax_u_per_s);
  CHECK(p->eco.accel_u_per_s2 == start.accel_u_per_s2);
  CHECK(price_of(p->eco, Item::speed) == 100);
  // Nobody else gained or lost anything.
  for (const Player& q : before) {
    const Player* now = find_player(s, q.id);
    REQUIRE(now);
    CHECK(now->eco.coins == q.eco.coins);
    CHECK(now->eco.spent == q.eco.spent);
  }
  // It plays at once, its ball under spawn protection.
  CHECK(p->ball != 0);
  CHECK(p->protected_at(s.tick));
}

TEST_CASE("Late join: out players do not count, an even count takes the middle, newcomers of one tick alike",
          "[match][late_join]") {
  MatchState s = at_level_8();
  find_player(s, 3)->eco.lives = 0;  // out: watching, not in the match
  TickInputs in = join(4);
  in.joins.push_back({5, "later"});
  step(s, in);
  CHECK(find_player(s, 4)->eco.coins == 2000);  // between 1000 and 3000
  CHECK(find_player(s, 5)->eco.coins == 2000);
  step(s, join(6));  // now 1000, 3000, 2000, 2000
  CHECK(find_player(s, 6)->eco.coins == 2000);
}

TEST_CASE("Late join: a reconnect or a come-back after quitting keeps its own economy", "[match][late_join]") {
  MatchState s = at_level_8();
  TickInputs away;
  away.away.push_back(2);
  away.quit.push_back(3);
  step(s, away);
  TickInputs back;
  back.back = {2, 3};
  step(s, back);
  CHECK(find_player(s, 2)->eco.coins == 200);
  CHECK(find_player(s, 2)->eco.spent == 2800);
  CHECK(find_player(s, 3)->eco.coins == 200);
  CHECK(find_player(s, 3)->eco.start_coins == 0);
}

TEST_CASE("Late join: in the lobby, and with late_join_share 0, the original start", "[match][late_join]") {
  MatchState lobby = make_match({}, 1);
  step(lobby, joins(2));
  CHECK(find_player(lobby, 2)->eco.coins == 0);

  MatchConfig cfg;
  cfg.late_join_share = 0.0;
  MatchState s = at_level_8(cfg);
  step(s, join(4));
  CHECK(find_player(s, 4)->eco.coins == 0);
  CHECK(find_player(s, 4)->eco.multiplier == 1.0);

  cfg.late_join_share = 0.5;
  MatchState half = at_level_8(cfg);
  step(half, join(4));
  CHECK(find_player(half, 4)->eco.coins == 500);
}

TEST_CASE("Late join: the median rule by itself", "[economy][late_join]") {
  const MatchConfig cfg;
  CHECK(late_start_economy(0, {}, cfg).coins == 0);
  CHECK(late_start_economy(0, {7}, cfg).coins == 7);
  CHECK(late_start_economy(0, {1, 2}, cfg).coins == 1);  // 1.5 rounded down
  CHECK(late_start_economy(0, {5, 1, 9}, cfg).coins == 5);
  CHECK(late_start_economy(0, {cfg.coin_cap, cfg.coin_cap}, cfg).coins == cfg.coin_cap);
  MatchConfig rich;
  rich.player_coins = 300;
  CHECK(late_start_economy(0, {100}, rich).coins == 300);  // never below the start
  // Growth stops at the caps: a huge level count costs no time.
  CHECK(late_start_economy(1'000'000'000'000, {}, cfg).multiplier == cfg.multiplier_cap);
}
