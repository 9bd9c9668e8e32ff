// The public state of a match, as a network snapshot needs it: plain values, ids, no
// internals (Rng, credit marks, goals stay on the server).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "fts/sim/match.hpp"

namespace fts::sim {

struct PlayerView {
  PlayerId id = 0;
  std::string name;
  Coins coins = 0;
  std::int64_t lives = 0;
  std::array<Coins, kItemCount> prices{};  // charged now, item table order
  std::int64_t mass = 0;
  double vmax_u_per_s = 0.0;
  double accel_u_per_s2 = 0.0;
  double multiplier = 1.0;
  bool bank = false;
  bool rockets = false;  // the weapon
  bool ready = false;
  bool alive = false;    // a ball on the platform
  bool out = false;      // no lives left: watching
  bool away = false;     // its client is gone (lost or quit) and may come back
  BallId ball = 0;
  // Spawn protection: the ball is immovable until this tick (-1: not protected).
  std::int64_t protected_until_tick = -1;
  std::int64_t purchases = 0;
  std::int64_t defeats = 0;
};

struct BallView {
  BallId id = 0;
  BodyKind kind = BodyKind::enemy;
  PlayerId owner = 0;  // player balls and rockets
  double x = 0, y = 0, vx = 0, vy = 0, radius = 0, mass = 0;
};

struct MatchView {
  std::int64_t tick = 0;
  Phase phase = Phase::lobby;
  std::int64_t level = 0;
  std::int64_t levels_cleared = 0;
  std::int64_t shop_ticks_left = 0;  // shop phase only
  // The tick at which the lobby or the shop stops waiting (-1: no countdown running).
  std::int64_t deadline_tick = -1;
  std::vector<PlayerView> players;   // by id
  std::vector<BallView> balls;       // by id
};

MatchView make_view(const MatchState& s);

}  // namespace fts::sim
