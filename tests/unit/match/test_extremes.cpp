// "Numbers that must not break": level 10 000, 10 000 purchases of one item, a bank
// compounding for 10 000 levels. Coins and prices saturate at cfg.coin_cap (10^15), the
// multiplier at cfg.multiplier_cap (10^9); nothing overflows, goes negative or is NaN.
#include <catch2/catch.hpp>

#include <cmath>

#include "fts/sim/level.hpp"
#include "fts/sim/shop_text.hpp"
#include "match_test_util.hpp"

using namespace fts::sim;
using namespace fts::test;

TEST_CASE("Extremes: saturating arithmetic") {
  const Coins cap = MatchConfig{}.coin_cap;
  CHECK(sat_add(cap, cap, cap) == cap);
  CHECK(sat_add(cap - 1, 1, cap) == cap);
  CHECK(sat_add(INT64_MAX, INT64_MAX, cap) == cap);
  CHECK(sat_add(-5, 3, cap) == 3);
  CHECK(floor_mul(cap, 1e300, cap) == cap);
  CHECK(floor_mul(cap, 0.5, cap) == cap / 2);
  CHECK(floor_mul(-7, 2.0, cap) == 0);
  CHECK(floor_clamp(std::nan(""), cap) == 0);
  CHECK(floor_clamp(-1e300, cap) == 0);
  CHECK(floor_clamp(1e300, cap) == cap);
}

TEST_CASE("Extremes: level 10000") {
  const MatchConfig cfg;
  Rng rng(3);
  for (std::int64_t L : {9999, 10000, 10005, 10001, 1'000'000}) {
    INFO("L = " << L);
    const std::int64_t n = enemy_count(L, cfg);
    CHECK(n >= 1);
    CHECK(enemy_count_for_players(L, 8, cfg) <= 48);
    for (std::int64_t i = 0; i < n; ++i) {
      const EnemySpec e = enemy_spec(L, i, rng, cfg);
      CHECK(std::isfinite(e.mass));
      CHECK(e.mass > 0);
      CHECK(e.radius_u > 0);
      CHECK(std::isfinite(e.vmax_u_per_s));
      CHECK(e.vmax_u_per_s >= 0);
      CHECK(e.accel_u_per_s2 >= 0);
      const Coins r = defeat_reward(e.mass, cfg.multiplier_cap, L, is_boss_level(L, cfg), cfg);
      CHECK(r > 0);
      CHECK(r <= cfg.coin_cap);
    }
  }
  // A match actually played at level 10000 with 8 players (48 big enemies do not fit in
  // the spawn box: the spawn falls back and the physics separates them).
  MatchState s = started(8, 9);
  s.phase = Phase::shop;
  s.level = 9999;
  s.shop_deadline_tick = s.tick;
  run(s, 1);
  REQUIRE(s.level == 10000);
  for (std::uint32_t p = 1; p <= 8; ++p) find_player(s, p)->eco.multiplier = s.cfg.multiplier_cap;
  run(s, 500);
  CHECK(all_finite(s.world.balls));
  for (const Player& p : s.players) {
    CHECK(p.eco.coins >= 0);
    CHECK(p.eco.coins <= s.cfg.coin_cap);
  }
}

TEST_CASE("Extremes: 10000 purchases of each item") {
  const MatchConfig cfg;
  for (const ItemDef& row : item_table()) {
    const Item item = row.item;
    INFO("item " << to_string(item));
    Economy e = start_economy(cfg);
    Coins last_price = price_of(e, item);
    int ok = 0;
    for (int i = 0; i < 10000; ++i) {
      e.coins = cfg.coin_cap;
      const Purchase p = buy(e, item, 10000, cfg);
      ok += p.ok;
      REQUIRE(p.price >= 1);
      REQUIRE(p.price <= cfg.coin_cap);
      REQUIRE(e.coins >= 0);
      const Coins now = price_of(e, item);
      REQUIRE(now >= 1);
      REQUIRE(now <= cfg.coin_cap);
      REQUIRE(now >= last_price);  // at level 10000 every price grows or stays
      last_price = now;
    }
    CHECK(ok == ((item == Item::rockets || item == Item::bank) ? 1 : 10000));
    CHECK(std::isfinite(e.multiplier));
    CHECK(e.multiplier <= cfg.multiplier_cap);
    CHECK(e.vmax_u_per_s <= cfg.player_vmax_cap_u_per_s);
    CHECK(e.accel_u_per_s2 <= cfg.player_accel_cap_u_per_s2);
    CHECK(e.mass <= cfg.player_mass_cap);
    CHECK(e.lives <= cfg.lives_cap);
    for (const auto& line : shop_lines(e, 10000)) CHECK_FALSE(line.find("nan") != std::string::npos);
  }
  // 10000 purchases at level 1 where the mass price falls: it stops at one coin.
  Economy e = start_economy(cfg);
  for (int i = 0; i < 10000; ++i) {
    e.coins = 100;
    REQUIRE(buy(e, Item::mass, 1, cfg).ok);
  }
  CHECK(price_of(e, Item::mass) == 1);
  CHECK(e.mass == 10040);
}

TEST_CASE("Extremes: a bank compounding for 10000 levels saturates at the cap") {
  const MatchConfig cfg;
  Economy e = start_economy(cfg);
  e.coins = 1000;
  e.start_coins = 1000;
  e.bank = true;
  Coins prev = e.coins;
  double prev_mult = e.multiplier;
  for (int L = 1; L <= 10000; ++L) {
    complete_level(e, cfg);
    REQUIRE(e.coins >= prev);
    REQUIRE(e.coins <= cfg.coin_cap);
    REQUIRE(e.multiplier >= prev_mult);
    REQUIRE(e.multiplier <= cfg.multiplier_cap);
    REQUIRE(std::isfinite(e.prices[Item::life]));
    REQUIRE(e.prices[Item::life] <= static_cast<double>(cfg.coin_cap));
    prev = e.coins;
    prev_mult = e.multiplier;
  }
  CHECK(e.coins == cfg.coin_cap);
  CHECK(e.multiplier == cfg.multiplier_cap);
  CHECK(price_of(e, Item::life) == cfg.coin_cap);
  CHECK(e.coins == e.start_coins + e.earned_defeats + e.earned_interest - e.spent);
  // Earning at the cap stays at the cap.
  CHECK(earn_defeat(e, cfg.coin_cap, cfg) == 0);
  CHECK(e.coins == cfg.coin_cap);
  CHECK(shop_lines(e, 10000)[1] == "Coins: 1,000,000,000,000,000");
}
