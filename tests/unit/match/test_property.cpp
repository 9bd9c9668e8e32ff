// Property over random matches (bots and random players, random configurations, joins,
// leaves, purchases, play-again): no coin count goes negative, no purchase happens without
// the coins, nothing becomes NaN, and coins held = start + earned (defeats + interest) -
// spent, per player, at every tick.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "fts/sim/bot_player.hpp"
#include "match_test_util.hpp"

using namespace fts::sim;
using namespace fts::test;

namespace {

struct Stats {
  std::int64_t ticks = 0, purchases_ok = 0, purchases_refused = 0, defeats = 0, levels = 0;
};

void random_match(std::uint64_t seed, int ticks, Stats& st) {
  Rng r(seed * 7919 + 1);
  MatchConfig cfg;
  const double rates[] = {50.0, 100.0, 200.0};
  cfg.tick_rate_hz = rates[r.uniform_int(0, 2)];
  const Model models[] = {Model::continuous, Model::continuous, Model::discrete, Model::seed};
  cfg.model = models[r.uniform_int(0, 3)];
  const Coins start_coins[] = {0, 0, 300, 5000, 2'000'000};
  cfg.player_coins = start_coins[r.uniform_int(0, 4)];
  cfg.shop_timeout_s = 0.5;
  cfg.max_players = 4;
  const int players = static_cast<int>(r.uniform_int(1, 4));
  std::vector<bool> is_bot(5);
  for (int i = 1; i <= 4; ++i) is_bot[i] = r.uniform_int(0, 2) != 0;
  const char* items[] = {"m", "s", "a", "r", "l", "x", "b", "mass", "bank", "laser", ""};

  MatchState s = make_match(cfg, seed);
  std::map<PlayerId, Coins> defeat_coins;  // from events, since the player's economy began
  for (int t = 0; t < ticks; ++t) {
    TickInputs in;
    if (t == 0) in = joins(players);
    for (std::uint32_t id = 1; id <= 4; ++id) {
      const bool present = find_player(s, id) != nullptr;
      if (t > 0 && !present && id <= static_cast<std::uint32_t>(players) && r.uniform01() < 0.002)
        in.joins.push_back({id, "re" + std::to_string(id)});
      if (present && r.uniform01() < 0.0005) in.leaves.push_back(id);
    }
    for (const Player& p : s.players) {
      PlayerTick pt;
      if (is_bot[p.id.value]) {
        pt = bot_tick(s, p.id);
      } else {
        pt.player = p.id;
        pt.input.move_x = static_cast<std::int8_t>(r.uniform_int(-1, 1));
        pt.input.move_y = static_cast<std::int8_t>(r.uniform_int(-1, 1));
        pt.input.fire = r.uniform01() < 0.05;
      }
      if (r.uniform01() < 0.05) pt.commands.push_back(buy(items[r.uniform_int(0, 10)]));
      if (r.uniform01() < 0.01) pt.commands.push_back({CommandKind::ready, {}});
      if (r.uniform01() < 0.002) pt.commands.push_back({CommandKind::play_again, {}});
      in.players.push_back(std::move(pt));
    }
    std::map<PlayerId, Coins> before;
    for (const Player& p : s.players) before[p.id] = p.eco.coins;
    const auto events = step(s, in).events;
    ++st.ticks;
    bool new_economies = false;
    for (const Event& e : events) {
      const auto* started = std::get_if<LevelStarted>(&e);
      if ((started && started->level == 1 && !started->restart) || std::holds_alternative<Joined>(e))
        new_economies = true;
    }
    if (new_economies) {  // economies were reset this tick: take their totals as the new base
      defeat_coins.clear();
      for (const Player& p : s.players) defeat_coins[p.id] = p.eco.earned_defeats;
    }
    for (const Event& event : events) {
      if (const auto* d = std::get_if<EnemyDefeated>(&event)) {
        ++st.defeats;
        if (d->player && !new_economies) defeat_coins[d->player] += d->coins;  // else re-read below
        REQUIRE(d->coins >= 0);
      }
      if (std::holds_alternative<LevelComplete>(event)) ++st.levels;
      const auto* bought = std::get_if<Purchased>(&event);
      if (!bought) continue;
      const Purchased& e = *bought;
      REQUIRE(e.coins_after >= 0);
      if (e.ok) {
        ++st.purchases_ok;
        REQUIRE(e.price >= 1);
        if (!new_economies) {
          REQUIRE(before[e.player] >= e.price);  // never without the coins
          REQUIRE(e.coins_after == before[e.player] - e.price);
          before[e.player] = e.coins_after;
        }
      } else {
        ++st.purchases_refused;
        if (!new_economies) REQUIRE(e.coins_after == before[e.player]);
        if (e.reason == Refusal::not_enough_coins) REQUIRE(e.coins_after < e.price);
      }
    }
    for (const Player& p : s.players) {
      const Economy& e = p.eco;
      REQUIRE(e.coins >= 0);
      REQUIRE(e.coins <= cfg.coin_cap);
      REQUIRE(e.lives >= 0);
      REQUIRE(e.coins == e.start_coins + e.earned_defeats + e.earned_interest - e.spent);
      REQUIRE(defeat_coins[p.id] == e.earned_defeats);
      REQUIRE(std::isfinite(e.multiplier));
      REQUIRE(std::isfinite(e.prices[Item::life]));
      REQUIRE(std::isfinite(e.vmax_u_per_s));
    }
    REQUIRE(all_finite(s.world.balls));
  }
}

void property(int matches, int ticks) {
  Stats st;
  for (int m = 1; m <= matches; ++m) {
    INFO("match seed " << m);
    random_match(static_cast<std::uint64_t>(m), ticks, st);
  }
  WARN("ticks " << st.ticks << ", purchases ok " << st.purchases_ok << ", refused " << st.purchases_refused
                << ", defeats " << st.defeats << ", levels cleared " << st.levels);
  CHECK(st.purchases_ok > 0);
  CHECK(st.purchases_refused > 0);
  CHECK(st.defeats > 0);
}

}  // namespace

// About 5 s in RelWithDebInfo on this machine, so it stays in the default run: matches
// 1-1000 in the optimized build. Under AddressSanitizer the same code takes about 100 s,
// the slowest of the test command's unit tests, so the sanitized build plays matches
// 1-100: the memory checks see every path the rules take in a hundred random matches,
// and the optimized build keeps the full thousand's statistics.
#ifdef __SANITIZE_ADDRESS__
constexpr int kMatches = 100;
#else
constexpr int kMatches = 1000;
#endif
TEST_CASE("Property: random matches keep coins sane (1000 x 2000 ticks, 100 sanitized)") {
  property(kMatches, 2000);
}

// Longer matches reach later levels, bosses, swarms and the bank's compounding.
TEST_CASE("Property: random matches keep coins sane (200 x 20000 ticks)", "[.][soak]") {
  property(200, 20000);
}
