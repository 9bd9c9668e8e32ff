#include "fts/sim/economy.hpp"

#include <algorithm>
#include <cmath>

namespace fts::sim {

std::string_view to_string(Refusal r) { return refusal_info(r).name; }

Coins sat_add(Coins a, Coins b, Coins cap) {
  a = std::clamp<Coins>(a, 0, cap);
  b = std::clamp<Coins>(b, 0, cap);
  return a > cap - b ? cap : a + b;
}

Coins floor_clamp(double x, Coins cap) {
  if (!(x > 0.0)) return 0;  // also NaN
  if (!(x < static_cast<double>(cap))) return cap;
  return static_cast<Coins>(std::floor(x));
}

Coins floor_mul(Coins a, double f, Coins cap) {
  if (a <= 0) return 0;
  return floor_clamp(static_cast<double>(a) * f, cap);
}

Economy start_economy(const MatchConfig& cfg) {
  Economy e;
  e.coins = std::clamp<Coins>(cfg.player_coins, 0, cfg.coin_cap);
  e.start_coins = e.coins;
  e.lives = cfg.player_lives;
  e.mass = cfg.player_mass;
  e.vmax_u_per_s = cfg.player_vmax_u_per_s;
  e.accel_u_per_s2 = cfg.player_accel_u_per_s2;
  e.multiplier = cfg.player_multiplier;
  for (const ItemDef& d : item_table()) e.prices[d.item] = static_cast<double>(cfg.*d.start_price);
  return e;
}

Coins total_value(const Economy& e, const MatchConfig& cfg) { return sat_add(e.coins, e.spent, cfg.coin_cap); }

Economy late_start_economy(std::int64_t levels_cleared, std::vector<Coins> values, const MatchConfig& cfg) {
  Economy e = start_economy(cfg);
  for (std::int64_t i = 0; i < levels_cleared; ++i) {
    const double multiplier = e.multiplier, life = e.prices[Item::life];
    complete_level(e, cfg);  // no bank: no interest, only the growth
    if (e.multiplier == multiplier && e.prices[Item::life] == life) break;  // at the caps (or factors of 1)
  }
  if (!values.empty()) {
    std::sort(values.begin(), values.end());
    const std::size_t mid = values.size() / 2;
    Coins median = values[mid];
    if (values.size() % 2 == 0) median = values[mid - 1] + (values[mid] - values[mid - 1]) / 2;
    e.coins = std::max(e.coins, floor_mul(median, cfg.late_join_share, cfg.coin_cap));
    e.start_coins = e.coins;  // a grant, not earned: coins == start + earned - spent still
  }
  return e;
}

Coins price_of(const Economy& e, Item item) {
  const Coins big = 1'000'000'000'000'000'000;  // above any cap; clamped below
  return floor_clamp(e.prices[item], big);
}

double clamp_double(double v, double lo, double hi) {
  if (!(v >= lo)) return lo;  // also NaN
  return v > hi ? hi : v;
}

Purchase buy(Economy& e, Item item, std::int64_t level, const MatchConfig& cfg) {
  Purchase p;
  p.item = item;
  p.price = price_of(e, item);
  p.coins_after = e.coins;
  const ItemDef& d = item_def(item);
  if (d.owned && d.owned(e)) {
    p.reason = Refusal::already_owned;
    return p;
  }
  if (e.coins < p.price) {
    p.reason = Refusal::not_enough_coins;
    return p;
  }
  d.effect(e, cfg);
  if (d.next_price) e.prices[item] = d.next_price(e.prices[item], level, cfg);
  const Coins cap = cfg.coin_cap;
  e.coins -= p.price;
  e.spent = sat_add(e.spent, p.price, cap);
  ++e.purchases;
  p.ok = true;
  p.coins_after = e.coins;
  return p;
}

Coins defeat_reward(double enemy_mass, double multiplier, std::int64_t level, bool boss, const MatchConfig& cfg) {
  const Coins cap = cfg.coin_cap;
  const Coins base = floor_clamp(enemy_mass * multiplier, cap);
  Coins r = sat_add(base, std::clamp<Coins>(level, 0, cap), cap);
  r = sat_add(r, cfg.reward_level_bonus, cap);
  if (boss) r = sat_add(r, base, cap);
  return r;
}

Coins earn_defeat(Economy& e, Coins reward, const MatchConfig& cfg) {
  const Coins before = e.coins;
  e.coins = sat_add(e.coins, reward, cfg.coin_cap);
  e.earned_defeats = sat_add(e.earned_defeats, e.coins - before, cfg.coin_cap);
  ++e.defeats;
  return e.coins - before;
}

void complete_level(Economy& e, const MatchConfig& cfg) {
  const double dcap = static_cast<double>(cfg.coin_cap);
  if (e.bank) {
    const Coins before = e.coins;
    e.coins = std::max(before, floor_mul(e.coins, cfg.bank_interest_factor, cfg.coin_cap));
    e.earned_interest = sat_add(e.earned_interest, e.coins - before, cfg.coin_cap);
  }
  e.multiplier = clamp_double(e.multiplier * cfg.level_multiplier_growth, 0.0, cfg.multiplier_cap);
  e.prices[Item::life] = clamp_double(e.prices[Item::life] * cfg.level_life_price_growth, 1.0, dcap);
}

}  // namespace fts::sim
