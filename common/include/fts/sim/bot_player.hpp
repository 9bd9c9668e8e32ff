// A built-in bot: a deterministic controller that reads the match state and fills the
// same PlayerTick a human's client would. In play it pushes the nearest enemy toward
// that enemy's nearest edge while keeping itself on the platform; in the shop it buys
// what it can afford (a life when low, the bank, acceleration, speed, mass) and readies.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "fts/sim/match.hpp"

namespace fts::sim {

PlayerTick bot_tick(const MatchState& s, PlayerId id);

// What the bot's steering needs to see, whatever it is read from (the match state here,
// a network snapshot in fts-bot): shared so that both bots play the same way.
struct BotSight {
  Ball me;
  std::vector<Ball> enemies;
  double vmax_u_per_s = 170.0;
  double accel_u_per_s2 = 200.0;
  bool rockets = false;
  double arena_width_u = 500.0;
  double arena_height_u = 300.0;
};
// Thrust (and fire) that pushes the nearest enemy toward its nearest edge while keeping
// the bot's own ball on the platform.
PlayerInput bot_play_input(const BotSight& sight);

// What the bot's shopping needs to see; prices in item table order (as on the wire).
struct ShopSight {
  Coins coins = 0;
  std::int64_t lives = 0;
  bool bank = false;
  double accel_u_per_s2 = 0, vmax_u_per_s = 0;
  std::int64_t mass = 0;
  std::array<Coins, kItemCount> prices{};
  double start_accel_u_per_s2 = 200, start_vmax_u_per_s = 170;
  std::int64_t start_mass = 40;
};
// The item the bot buys next (a life when low, the bank, acceleration, speed, mass), or
// none when it should send ready.
std::optional<Item> bot_shop_choice(const ShopSight& sight);

}  // namespace fts::sim
