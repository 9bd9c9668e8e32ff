// GAME_RULES.md "Coins, shop and lives": rewards, level-end growth, the shop's price rules,
// refusals, and the shop screen of the seed.
#include <catch2/catch.hpp>

#include "../../support/seed_shop_lines.hpp"
#include "fts/sim/economy.hpp"
#include "fts/sim/shop_text.hpp"

using namespace fts::sim;

namespace {

std::vector<Coins> price_sequence(Item item, std::int64_t level, int buys) {
  const MatchConfig cfg;
  Economy e = start_economy(cfg);
  std::vector<Coins> prices;
  for (int i = 0; i < buys; ++i) {
    e.coins = cfg.coin_cap;
    prices.push_back(price_of(e, item));
    REQUIRE(buy(e, item, level, cfg).ok);
  }
  prices.push_back(price_of(e, item));
  return prices;
}

}  // namespace

TEST_CASE("Coins, shop and lives: start values") {
  const Economy e = start_economy(MatchConfig{});
  CHECK(e.coins == 0);
  CHECK(e.lives == 3);
  CHECK(e.mass == 40);
  CHECK(e.vmax_u_per_s == 170.0);
  CHECK(e.accel_u_per_s2 == 200.0);
  CHECK(e.multiplier == 1.0);
  CHECK_FALSE(e.bank);
  CHECK_FALSE(e.rockets);
  CHECK(price_of(e, Item::mass) == 35);
  CHECK(price_of(e, Item::speed) == 100);
  CHECK(price_of(e, Item::accel) == 150);
  CHECK(price_of(e, Item::rockets) == 1'000'000);
  CHECK(price_of(e, Item::life) == 500);
  CHECK(price_of(e, Item::multiplier) == 100);
  CHECK(price_of(e, Item::bank) == 500);
}

TEST_CASE("Coins, shop and lives: price sequence after repeated purchases") {
  CHECK(price_sequence(Item::mass, 3, 3) == std::vector<Coins>{35, 35, 35, 35});      // floor(p + 1.65 - 1)
  CHECK(price_sequence(Item::mass, 10, 3) == std::vector<Coins>{35, 39, 43, 47});     // + floor(4.5)
  CHECK(price_sequence(Item::mass, 1, 3) == std::vector<Coins>{35, 34, 33, 32});      // floor(p - 0.45)
  CHECK(price_sequence(Item::speed, 1, 5) == std::vector<Coins>{100, 120, 144, 172, 206, 247});
  CHECK(price_sequence(Item::accel, 1, 4) == std::vector<Coins>{150, 180, 216, 259, 310});
  CHECK(price_sequence(Item::life, 1, 4) == std::vector<Coins>{500, 550, 605, 665, 731});
  CHECK(price_sequence(Item::multiplier, 1, 4) == std::vector<Coins>{100, 150, 225, 337, 506});
}

TEST_CASE("Coins, shop and lives: purchase effects") {
  const MatchConfig cfg;
  Economy e = start_economy(cfg);
  e.coins = 10'000'000;
  REQUIRE(buy(e, Item::mass, 3, cfg).ok);
  CHECK(e.mass == 41);
  REQUIRE(buy(e, Item::speed, 3, cfg).ok);
  CHECK(e.vmax_u_per_s == Approx(178.5));
  REQUIRE(buy(e, Item::accel, 3, cfg).ok);
  CHECK(e.accel_u_per_s2 == Approx(210.0));
  REQUIRE(buy(e, Item::life, 3, cfg).ok);
  CHECK(e.lives == 4);
  REQUIRE(buy(e, Item::multiplier, 3, cfg).ok);
  CHECK(e.multiplier == Approx(1.1));
  REQUIRE(buy(e, Item::bank, 3, cfg).ok);
  CHECK(e.bank);
  REQUIRE(buy(e, Item::rockets, 3, cfg).ok);
  CHECK(e.rockets);
  CHECK(e.coins == 10'000'000 - 35 - 100 - 150 - 500 - 100 - 500 - 1'000'000);
  CHECK(e.spent == 35 + 100 + 150 + 500 + 100 + 500 + 1'000'000);
  CHECK(e.purchases == 7);
}

TEST_CASE("Coins, shop and lives: a refusal carries a reason and changes nothing") {
  const MatchConfig cfg;
  Economy e = start_economy(cfg);
  e.coins = 40;
  const Economy before = e;
  Purchase p = buy(e, Item::speed, 1, cfg);
  CHECK_FALSE(p.ok);
  CHECK(p.reason == Refusal::not_enough_coins);
  CHECK(p.price == 100);
  CHECK(p.coins_after == 40);
  CHECK(e.coins == before.coins);
  CHECK(e.vmax_u_per_s == before.vmax_u_per_s);
  CHECK(e.prices[Item::speed] == before.prices[Item::speed]);
  CHECK(e.purchases == 0);
  e.coins = 2000;
  REQUIRE(buy(e, Item::bank, 1, cfg).ok);
  p = buy(e, Item::bank, 1, cfg);
  CHECK_FALSE(p.ok);
  CHECK(p.reason == Refusal::already_owned);
  CHECK(e.coins == 1500);
  // Exactly enough coins is enough.
  e.coins = 35;
  CHECK(buy(e, Item::mass, 1, cfg).ok);
  CHECK(e.coins == 0);
  CHECK(parse_item("m") == Item::mass);
  CHECK(parse_item("multiplier") == Item::multiplier);
  CHECK(parse_item("x") == Item::multiplier);
  CHECK_FALSE(parse_item("laser"));
}

TEST_CASE("Coins, shop and lives: defeat reward floor(mass x multiplier) + L + 5, boss twice") {
  const MatchConfig cfg;
  CHECK(defeat_reward(30, 1.0, 1, false, cfg) == 36);
  CHECK(defeat_reward(37, 1.0612, 3, false, cfg) == 39 + 3 + 5);
  CHECK(defeat_reward(100, 1.0612, 10, true, cfg) == 106 + 10 + 5 + 106);
}

TEST_CASE("Coins, shop and lives: level end: bank interest, multiplier x1.02, life price x1.015") {
  const MatchConfig cfg;
  Economy e = start_economy(cfg);
  e.coins = 286;
  complete_level(e, cfg);
  CHECK(e.coins == 286);  // no bank
  CHECK(e.multiplier == Approx(1.02));
  CHECK(e.prices[Item::life] == Approx(507.5));
  e.bank = true;
  complete_level(e, cfg);
  CHECK(e.coins == 314);  // floor(286 x 1.1)
  CHECK(e.earned_interest == 28);
  CHECK(e.coins == e.start_coins + e.earned_defeats + e.earned_interest - e.spent + 286);
}

TEST_CASE("Coins, shop and lives: the shop screen of the seed (level 3, 286 coins, 1 life)") {
  const MatchConfig cfg;
  Economy e = start_economy(cfg);
  for (int L = 1; L <= 3; ++L) complete_level(e, cfg);
  e.coins = 286;
  e.lives = 1;
  const std::vector<std::string>& expected = fts::test::seed_shop_lines();
  CHECK(shop_lines(e, 3) == expected);
  CHECK(with_thousands(0) == "0");
  CHECK(with_thousands(999) == "999");
  CHECK(with_thousands(1000) == "1,000");
  CHECK(with_thousands(1'000'000'000'000'000) == "1,000,000,000,000,000");
  CHECK(fixed2(1.7) == "1.70");
}
