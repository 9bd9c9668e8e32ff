// Per-player economy: coins, prices, upgrades, lives. Integers with saturating arithmetic:
// coins and prices live in [0, cfg.coin_cap] (default 10^15, exact in a double), the
// multiplier in (0, cfg.multiplier_cap]; speeds, masses and lives have caps too. Nothing
// here overflows, goes negative or becomes NaN, whatever the number of levels or buys.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fts/sim/config.hpp"
#include "fts/sim/items.hpp"

namespace fts::sim {

using Coins = std::int64_t;

enum class Refusal : std::uint8_t { none, not_enough_coins, already_owned, wrong_phase, unknown_item, no_player };

// Every refusal once: its name in logs and the sentence a player reads. One table: the
// server's results, its logs and fts-sim's output read it. The code a result carries on
// the wire is the protocol's (fts/protocol/codes.hpp; the server maps each refusal).
struct RefusalInfo {
  Refusal refusal;
  std::string_view name;      // logs: "not_enough_coins"
  std::string_view sentence;  // the result's message: "not enough coins"
};
inline constexpr std::array<RefusalInfo, 6> kRefusals{{
    {Refusal::none, "", "done"},
    {Refusal::not_enough_coins, "not_enough_coins", "not enough coins"},
    {Refusal::already_owned, "already_owned", "already owned (it is bought once)"},
    {Refusal::wrong_phase, "wrong_phase", "not now (wrong phase)"},
    {Refusal::unknown_item, "unknown_item", "no such item; the shop sells m s a r l x b"},
    {Refusal::no_player, "no_player", "not in the match"},
}};
static_assert(kRefusals.size() == static_cast<std::size_t>(Refusal::no_player) + 1);
constexpr const RefusalInfo& refusal_info(Refusal r) { return kRefusals[static_cast<std::size_t>(r) % kRefusals.size()]; }
std::string_view to_string(Refusal r);

// The current price of each item (its table row says the rule). A whole-price item holds
// an integer; life (x1.015 per level) and multiplier (x1.5 without a floor) grow
// fractionally and are charged floor(price).
struct Prices {
  std::array<double, kItemCount> by_item{};
  double& operator[](Item item) { return by_item[index_of(item)]; }
  double operator[](Item item) const { return by_item[index_of(item)]; }
};

struct Economy {
  Coins coins = 0;
  std::int64_t lives = 0;
  std::int64_t mass = 0;
  double vmax_u_per_s = 0.0;
  double accel_u_per_s2 = 0.0;
  double multiplier = 1.0;
  bool bank = false;
  bool rockets = false;
  Prices prices;
  // Bookkeeping: coins == start + earned_defeats + earned_interest - spent, always.
  Coins start_coins = 0;
  Coins earned_defeats = 0;
  Coins earned_interest = 0;
  Coins spent = 0;
  std::int64_t purchases = 0;
  std::int64_t defeats = 0;
};

struct Purchase {
  Item item = Item::mass;
  bool ok = false;
  Refusal reason = Refusal::none;
  Coins price = 0;
  Coins coins_after = 0;
};

// a + b clamped to [0, cap] (a, b >= 0).
Coins sat_add(Coins a, Coins b, Coins cap);
// floor(a * f) clamped to [0, cap] (a >= 0, f >= 0 finite).
Coins floor_mul(Coins a, double f, Coins cap);
// floor(x) clamped to [0, cap].
Coins floor_clamp(double x, Coins cap);
// v clamped to [lo, hi]; NaN becomes lo.
double clamp_double(double v, double lo, double hi);

Economy start_economy(const MatchConfig& cfg);
// A player's total value: the coins it holds plus those it spent in the shop.
Coins total_value(const Economy& e, const MatchConfig& cfg);
// The start of a player who joins a running match after `levels_cleared` levels, beside
// players still in the match whose total values are `values`: the start economy grown as
// complete_level grows everyone's at each level's end (multiplier, life price), with
// coins floor(cfg.late_join_share x the median of `values`) where that is more than the
// start coins. The median of an even count is the lower middle value plus half the gap,
// rounded down.
Economy late_start_economy(std::int64_t levels_cleared, std::vector<Coins> values, const MatchConfig& cfg);
// The price charged now for `item` (an integer number of coins).
Coins price_of(const Economy& e, Item item);
// Buys `item` after level `level` was completed; a refusal changes nothing.
Purchase buy(Economy& e, Item item, std::int64_t level, const MatchConfig& cfg);
// Coins for defeating an enemy: floor(mass x multiplier) + L + 5, and floor(mass x
// multiplier) again on a boss level.
Coins defeat_reward(double enemy_mass, double multiplier, std::int64_t level, bool boss,
                    const MatchConfig& cfg);
// Credits a defeat reward; returns the coins actually added (saturated).
Coins earn_defeat(Economy& e, Coins reward, const MatchConfig& cfg);
// End of a level: bank interest, multiplier x1.02, life price x1.015.
void complete_level(Economy& e, const MatchConfig& cfg);

}  // namespace fts::sim
