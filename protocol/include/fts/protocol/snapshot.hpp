// The public state of a match as the wire carries it: what a client may know. The server
// converts its match state into these structs; a client reconstructs them from deltas.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "fts/sim/items.hpp"

namespace fts::protocol {

enum class Phase : std::uint8_t { lobby = 0, play = 1, shop = 2, over = 3 };
enum class BallKind : std::uint8_t { enemy = 0, player = 1, rocket = 2 };
enum class Weapon : std::uint8_t { none = 0, rockets = 1 };

// Shop items are common's item table (fts/sim/items.hpp): an item's byte is its shop key,
// prices travel in table order. Index of a shop key in that order, or -1.
int shop_index(char item);

struct BallState {
  std::uint32_t id = 0;
  double x = 0, y = 0;    // u, lower-left origin
  double vx = 0, vy = 0;  // u/s
  double radius = 1;      // u
  double mass = 1;
  BallKind kind = BallKind::enemy;
  std::uint32_t owner = 0;  // player id for player balls and rockets, 0 for enemies

  bool operator==(const BallState&) const = default;
};

struct PlayerState {
  std::uint32_t id = 0;
  std::string name;
  std::int64_t coins = 0;  // 0 .. 10^15
  std::int32_t lives = 0;
  double mass = 40;
  double vmax_u_per_s = 170;
  double accel_u_per_s2 = 200;
  double multiplier = 1;
  bool bank = false;
  Weapon weapon = Weapon::none;
  std::array<std::int64_t, sim::kItemCount> prices{};  // current price per item, item table order
  bool ready = false;
  bool alive = false;  // has a ball on the platform
  // Spawn protection: the ball cannot be pushed until this tick; 0: not protected.
  std::uint32_t protected_until_tick = 0;
  bool away = false;  // its client is gone for now (lost or quit); it may come back

  bool operator==(const PlayerState&) const = default;
};

enum class EventKind : std::uint8_t {
  enemy_fell = 0,      // a: ball id, b: credited player (0: none), value: coins earned
  player_fell = 1,     // a: player id, b: ball id, value: lives left
  level_started = 2,   // value: level
  level_complete = 3,  // value: level
  purchase = 4,        // a: player id, b: item key (ASCII), value: price paid
  player_joined = 5,   // a: player id
  player_left = 6,     // a: player id
  rocket_fired = 7,    // a: player id, b: rocket ball id
  match_over = 8,      // value: level reached
  respawned = 9,       // a: player id, b: ball id
  interest = 10,       // a: player id, value: coins added by the bank
  level_restarted = 11,  // value: level
  count_
};

struct Event {
  std::uint32_t seq = 0;  // 1, 2, 3, ... per match: each event's identity on the wire
  std::uint32_t tick = 0;
  EventKind kind = EventKind::enemy_fell;
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  std::int64_t value = 0;

  bool operator==(const Event&) const = default;
};

struct Snapshot {
  std::uint32_t tick = 0;
  Phase phase = Phase::lobby;
  std::uint32_t level = 0;
  // The tick at which the lobby or the shop ends without waiting any longer (0: no
  // countdown running): a client shows (deadline_tick - tick) / tick_rate_hz seconds.
  std::uint32_t deadline_tick = 0;
  std::vector<BallState> balls;      // sorted by id
  std::vector<PlayerState> players;  // sorted by id
  std::vector<Event> events;         // recent events, oldest first (ascending seq)

  bool operator==(const Snapshot&) const = default;
};

// Rounds positions, velocities, radii and masses of balls to the 1/16 grid the wire
// uses, clamps them to the wire range, and sorts balls and players by id. What a client
// reconstructs equals quantize() of what the server sent.
Snapshot quantize(Snapshot snapshot);

}  // namespace fts::protocol
