// The item table: each row's price rule, effect and shop-screen wording (GAME_RULES.md,
// "Coins, shop and lives"; the seed's shop slide).
#include "fts/sim/items.hpp"

#include <algorithm>
#include <cmath>

#include "fts/sim/economy.hpp"
#include "fts/sim/shop_text.hpp"

namespace fts::sim {
namespace {

// A whole-coin price never drops below one coin (the mass rule lowers it on early levels).
// Prices are at most coin_cap (<= 10^15), so they are exact in a double.
double whole(Coins p, const MatchConfig& cfg) { return static_cast<double>(std::clamp<Coins>(p, 1, cfg.coin_cap)); }

// floor(price + 0.55 L - 1) == price + floor(0.55 L - 1) for an integer price.
double next_mass_price(double price, std::int64_t level, const MatchConfig& cfg) {
  const Coins cap = cfg.coin_cap;
  const double dcap = static_cast<double>(cap);
  const double step = clamp_double(std::floor(cfg.price_mass_level_coeff * static_cast<double>(level) -
                                              cfg.price_mass_offset), -dcap, dcap);
  const Coins s = static_cast<Coins>(step);
  const Coins p = static_cast<Coins>(price);
  return whole(s >= 0 ? sat_add(p, s, cap) : p + s, cfg);
}

double next_speed_price(double price, std::int64_t, const MatchConfig& cfg) {
  return whole(floor_mul(static_cast<Coins>(price), cfg.price_speed_growth, cfg.coin_cap), cfg);
}

double next_accel_price(double price, std::int64_t, const MatchConfig& cfg) {
  return whole(floor_mul(static_cast<Coins>(price), cfg.price_accel_growth, cfg.coin_cap), cfg);
}

double next_life_price(double price, std::int64_t, const MatchConfig& cfg) {
  return clamp_double(std::floor(price * cfg.price_life_growth), 1.0, static_cast<double>(cfg.coin_cap));
}

double next_multiplier_price(double price, std::int64_t, const MatchConfig& cfg) {
  return clamp_double(price * cfg.price_multiplier_growth, 1.0, static_cast<double>(cfg.coin_cap));
}

// The seed's shop shows speeds in its own units: max speed in u/frame, acceleration in
// u/frame^2 x 100. Divided by whole frames per second, so that the default frame (0.01 s)
// gives exactly v / 100.
constexpr double kAccelShownScale = 100.0;
double per_frame(double v_u_per_s, const ShopTerms& t) { return v_u_per_s / (1.0 / t.frame_s); }
double per_frame2_shown(double a_u_per_s2, const ShopTerms& t) {
  const double frames_per_s = 1.0 / t.frame_s;
  return a_u_per_s2 / (frames_per_s * frames_per_s / kAccelShownScale);
}

constexpr ItemDef kItems[kItemCount] = {
    {Item::mass, 'm', "mass", "mass", &MatchConfig::price_mass, next_mass_price, true, nullptr,
     [](Economy& e, const MatchConfig& cfg) { e.mass = std::min(e.mass + 1, cfg.player_mass_cap); },
     [](const Economy& e, const ShopTerms&) { return "Current Mass: " + with_thousands(e.mass); },
     "To increase Mass", nullptr},
    {Item::speed, 's', "speed", "max speed", &MatchConfig::price_speed, next_speed_price, true, nullptr,
     [](Economy& e, const MatchConfig& cfg) {
       e.vmax_u_per_s = clamp_double(e.vmax_u_per_s * cfg.speed_upgrade_factor, 0.0, cfg.player_vmax_cap_u_per_s);
     },
     [](const Economy& e, const ShopTerms& t) { return "Current Max Speed: " + fixed2(per_frame(e.vmax_u_per_s, t)); },
     "To increase Max Speed", nullptr},
    {Item::accel, 'a', "accel", "acceleration", &MatchConfig::price_accel, next_accel_price, true, nullptr,
     [](Economy& e, const MatchConfig& cfg) {
       e.accel_u_per_s2 = clamp_double(e.accel_u_per_s2 * cfg.accel_upgrade_factor, 0.0, cfg.player_accel_cap_u_per_s2);
     },
     [](const Economy& e, const ShopTerms& t) {
       return "Current Acceleration: " + fixed2(per_frame2_shown(e.accel_u_per_s2, t));
     },
     "To increase Acceleration", nullptr},
    {Item::rockets, 'r', "rockets", "rockets", &MatchConfig::price_rockets, nullptr, true,
     [](const Economy& e) { return e.rockets; }, [](Economy& e, const MatchConfig&) { e.rockets = true; },
     [](const Economy& e, const ShopTerms&) {
       return std::string("Current Weapon: ") + (e.rockets ? "ROCKETS." : "NONE.");
     },
     "To purchase rockets", nullptr},
    {Item::life, 'l', "life", "a life", &MatchConfig::price_life, next_life_price, false, nullptr,
     [](Economy& e, const MatchConfig& cfg) { e.lives = std::min(e.lives + 1, cfg.lives_cap); },
     [](const Economy& e, const ShopTerms&) { return "Current Lives: " + with_thousands(e.lives); },
     "To add a life", nullptr},
    {Item::multiplier, 'x', "multiplier", "multiplier", &MatchConfig::price_multiplier, next_multiplier_price,
     false, nullptr,
     [](Economy& e, const MatchConfig& cfg) {
       e.multiplier = clamp_double(e.multiplier * cfg.multiplier_upgrade_factor, 0.0, cfg.multiplier_cap);
     },
     [](const Economy& e, const ShopTerms&) { return "Current Multiplier: " + fixed2(e.multiplier); },
     "To increase multiplier",
     [](const ShopTerms& t) {
       return "Increases coins from enemies by " + percent_text(t.multiplier_upgrade_factor) + "%";
     }},
    {Item::bank, 'b', "bank", "bank", &MatchConfig::price_bank, nullptr, true,
     [](const Economy& e) { return e.bank; }, [](Economy& e, const MatchConfig&) { e.bank = true; },
     [](const Economy& e, const ShopTerms&) { return std::string("Bank Purchased: ") + (e.bank ? "True" : "False"); },
     "To purchase bank",
     [](const ShopTerms& t) { return "Earns " + percent_text(t.bank_interest_factor) + "% interest per round"; }},
};

constexpr bool table_in_enum_order() {
  for (std::size_t i = 0; i < kItemCount; ++i)
    if (index_of(kItems[i].item) != i) return false;
  return true;
}
static_assert(table_in_enum_order(), "kItems rows must follow the Item enum (the wire's price order)");

}  // namespace

ShopTerms shop_terms(const MatchConfig& cfg) {
  return {cfg.frame_s, cfg.multiplier_upgrade_factor, cfg.bank_interest_factor};
}

std::span<const ItemDef, kItemCount> item_table() { return kItems; }

const ItemDef& item_def(Item item) { return kItems[index_of(item)]; }

std::optional<Item> item_by_key(char key) {
  for (const ItemDef& d : kItems)
    if (d.key == key) return d.item;
  return std::nullopt;
}

std::optional<Item> parse_item(std::string_view s) {
  for (const ItemDef& d : kItems)
    if (s == d.id || (s.size() == 1 && s[0] == d.key)) return d.item;
  return std::nullopt;
}

std::string_view to_string(Item item) { return item_def(item).id; }

char shop_key(Item item) { return item_def(item).key; }

std::string percent_text(double factor) {
  std::string s = fixed2((factor - 1.0) * 100.0);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

}  // namespace fts::sim
