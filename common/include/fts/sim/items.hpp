// The shop's items, one row each, like ioquake3's bg_itemlist[]: the match (price rules,
// effects), the wire (item bytes, the order of prices), the HUD (names), the shop screen
// (its lines) and the bots all read this table, so an item is one row to add or change.
// The numbers a row uses are MatchConfig fields: a server's configuration changes them
// everywhere at once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "fts/sim/config.hpp"

namespace fts::sim {

struct Economy;

// Table order, which is also the wire's order of prices.
enum class Item : std::uint8_t { mass, speed, accel, rockets, life, multiplier, bank };
inline constexpr std::size_t kItemCount = 7;
inline constexpr std::size_t index_of(Item item) { return static_cast<std::size_t>(item); }

// The configuration the shop screen states in words ("Earns 10% interest per round",
// speeds in the original's per-frame units). The server sends these in its welcome, so
// a client prints its server's numbers.
struct ShopTerms {
  double frame_s = MatchConfig{}.frame_s;
  double multiplier_upgrade_factor = MatchConfig{}.multiplier_upgrade_factor;
  double bank_interest_factor = MatchConfig{}.bank_interest_factor;
  bool operator==(const ShopTerms&) const = default;
};
ShopTerms shop_terms(const MatchConfig& cfg);

struct ItemDef {
  Item item;
  char key;               // the shop key, also the item's byte on the wire
  std::string_view id;    // in commands, logs and records: "mass"
  std::string_view name;  // in sentences: "You bought max speed"
  // The price rule: the start price, and the price after a purchase made once level L
  // was completed (null: the price never changes).
  std::int64_t MatchConfig::*start_price;
  double (*next_price)(double price, std::int64_t level, const MatchConfig& cfg);
  // A price in whole coins (the state hash writes it as an integer); otherwise it grows
  // fractionally and floor(price) is charged.
  bool whole_price;
  // Bought once (rockets, bank): whether the player owns it; null for other items.
  bool (*owned)(const Economy& e);
  // What one purchase gives.
  void (*effect)(Economy& e, const MatchConfig& cfg);
  // The shop screen: the player's current value, the offer ("To add a life", followed by
  // the key and the price; not shown once owned) and an optional line under the offer.
  std::string (*status)(const Economy& e, const ShopTerms& terms);
  std::string_view offer;
  std::string (*note)(const ShopTerms& terms);
};

// Every item, in table order.
std::span<const ItemDef, kItemCount> item_table();
const ItemDef& item_def(Item item);
std::optional<Item> item_by_key(char key);
// "mass", "speed", ... and the shop keys "m", "s", ...
std::optional<Item> parse_item(std::string_view s);
std::string_view to_string(Item item);
char shop_key(Item item);
// (factor - 1) as a percentage with at most two decimals: 1.1 -> "10", 1.025 -> "2.5".
std::string percent_text(double factor);

}  // namespace fts::sim
