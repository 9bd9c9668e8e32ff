#include "fts/sim/economy.hpp"

#include <algorithm>
#include <cmath>

namespace fts::sim {

std::optional<Item> parse_item(std::string_view s) {
  for (Item it : kAllItems) {
    if (s == to_string(it) || (s.size() == 1 && s[0] == shop_key(it))) return it;
  }
  return std::nullopt;
}

std::string_view to_string(Item item) {
  switch (item) {
    case Item::mass: return "mass";
    case Item::speed: return "speed";
    case Item::accel: return "accel";
    case Item::rockets: return "rockets";
    case Item::life: return "life";
    case Item::multiplier: return "multiplier";
    case Item::bank: return "bank";
  }
  return "?";
}

char shop_key(Item item) {
  switch (item) {
    case Item::mass: return 'm';
    case Item::speed: return 's';
    case Item::accel: return 'a';
    case Item::rockets: return 'r';
    case Item::life: return 'l';
    case Item::multiplier: return 'x';
    case Item::bank: return 'b';
  }
  return '?';
}

std::string_view to_string(Refusal r) {
  switch (r) {
    case Refusal::none: return "";
    case Refusal::not_enough_coins: return "not_enough_coins";
    case Refusal::already_owned: return "already_owned";
    case Refusal::wrong_phase: return "wrong_phase";
    case Refusal::unknown_item: return "unknown_item";
    case Refusal::no_player: return "no_player";
  }
  return "?";
}

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
  e.prices.mass = cfg.price_mass;
  e.prices.speed = cfg.price_speed;
  e.prices.accel = cfg.price_accel;
  e.prices.rockets = cfg.price_rockets;
  e.prices.bank = cfg.price_bank;
  e.prices.life = static_cast<double>(cfg.price_life);
  e.prices.multiplier = static_cast<double>(cfg.price_multiplier);
  return e;
}

Coins price_of(const Economy& e, Item item) {
  const Coins big = 1'000'000'000'000'000'000;  // above any cap; clamped below
  switch (item) {
    case Item::mass: return e.prices.mass;
    case Item::speed: return e.prices.speed;
    case Item::accel: return e.prices.accel;
    case Item::rockets: return e.prices.rockets;
    case Item::bank: return e.prices.bank;
    case Item::life: return floor_clamp(e.prices.life, big);
    case Item::multiplier: return floor_clamp(e.prices.multiplier, big);
  }
  return 0;
}

namespace {

// A price never drops below one coin (the mass rule decreases it on early levels).
Coins clamp_price(Coins p, const MatchConfig& cfg) { return std::clamp<Coins>(p, 1, cfg.coin_cap); }

double clamp_double(double v, double lo, double hi) {
  if (!(v >= lo)) return lo;  // also NaN
  return v > hi ? hi : v;
}

}  // namespace

Purchase buy(Economy& e, Item item, std::int64_t level, const MatchConfig& cfg) {
  Purchase p;
  p.item = item;
  p.price = price_of(e, item);
  p.coins_after = e.coins;
  if ((item == Item::rockets && e.rockets) || (item == Item::bank && e.bank)) {
    p.reason = Refusal::already_owned;
    return p;
  }
  if (e.coins < p.price) {
    p.reason = Refusal::not_enough_coins;
    return p;
  }
  const Coins cap = cfg.coin_cap;
  const double dcap = static_cast<double>(cap);
  switch (item) {
    case Item::mass: {
      e.mass = std::min(e.mass + 1, cfg.player_mass_cap);
      // floor(price + 0.55 L - 1) == price + floor(0.55 L - 1) for an integer price.
      const double step = clamp_double(std::floor(cfg.price_mass_level_coeff * static_cast<double>(level) -
                                                  cfg.price_mass_offset), -dcap, dcap);
      const Coins s = static_cast<Coins>(step);
      e.prices.mass = clamp_price(s >= 0 ? sat_add(e.prices.mass, s, cap) : e.prices.mass + s, cfg);
      break;
    }
    case Item::speed:
      e.vmax_u_per_s = clamp_double(e.vmax_u_per_s * cfg.speed_upgrade_factor, 0.0, cfg.player_vmax_cap_u_per_s);
      e.prices.speed = clamp_price(floor_mul(e.prices.speed, cfg.price_speed_growth, cap), cfg);
      break;
    case Item::accel:
      e.accel_u_per_s2 = clamp_double(e.accel_u_per_s2 * cfg.accel_upgrade_factor, 0.0, cfg.player_accel_cap_u_per_s2);
      e.prices.accel = clamp_price(floor_mul(e.prices.accel, cfg.price_accel_growth, cap), cfg);
      break;
    case Item::rockets: e.rockets = true; break;
    case Item::bank: e.bank = true; break;
    case Item::life:
      e.lives = std::min(e.lives + 1, cfg.lives_cap);
      e.prices.life = clamp_double(std::floor(e.prices.life * cfg.price_life_growth), 1.0, dcap);
      break;
    case Item::multiplier:
      e.multiplier = clamp_double(e.multiplier * cfg.multiplier_upgrade_factor, 0.0, cfg.multiplier_cap);
      e.prices.multiplier = clamp_double(e.prices.multiplier * cfg.price_multiplier_growth, 1.0, dcap);
      break;
  }
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
  e.prices.life = clamp_double(e.prices.life * cfg.level_life_price_growth, 1.0, dcap);
}

}  // namespace fts::sim
