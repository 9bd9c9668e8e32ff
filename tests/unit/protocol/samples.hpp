// Sample messages and snapshots shared by the protocol tests.
#pragma once

#include <cstdint>
#include <vector>

#include "fts/protocol/messages.hpp"
#include "fts/protocol/snapshot.hpp"

namespace fts::protocol::test {

inline Snapshot sample_snapshot(int players, int enemies, std::uint32_t tick = 100, std::uint32_t seed = 1) {
  Snapshot s;
  s.tick = tick;
  s.phase = Phase::play;
  s.level = 7;
  std::uint32_t r = seed * 2654435761u + 12345u;
  auto next = [&r]() {
    r = r * 1664525u + 1013904223u;
    return static_cast<double>(r >> 8) / static_cast<double>(1u << 24);
  };
  std::uint32_t id = 1;
  for (int p = 1; p <= players; ++p) {
    BallState b;
    b.id = id++;
    b.x = 20 + 150 * next();
    b.y = 30 + 240 * next();
    b.vx = -170 + 340 * next();
    b.vy = -170 + 340 * next();
    b.mass = 40 + p;
    b.radius = 11 + (40 + p) / 8;
    b.kind = BallKind::player;
    b.owner = static_cast<std::uint32_t>(p);
    s.balls.push_back(b);
    PlayerState ps;
    ps.id = static_cast<std::uint32_t>(p);
    ps.name = "player-" + std::to_string(p);
    ps.coins = 1234 * p;
    ps.lives = 3;
    ps.mass = 40 + p;
    ps.vmax_u_per_s = 170 * 1.05;
    ps.accel_u_per_s2 = 200;
    ps.multiplier = 1.02 * 1.02 * 1.1;
    ps.bank = p % 2 == 0;
    ps.prices = {35 + p, 100, 150, 1'000'000, 500, 150, 500};
    ps.ready = false;
    ps.alive = true;
    s.players.push_back(ps);
  }
  for (int e = 0; e < enemies; ++e) {
    BallState b;
    b.id = id++;
    b.x = 50 + 400 * next();
    b.y = 50 + 200 * next();
    b.vx = -120 + 240 * next();
    b.vy = -120 + 240 * next();
    b.mass = 42 + e % 4;
    b.radius = 16;
    b.kind = BallKind::enemy;
    s.balls.push_back(b);
  }
  s.events.push_back({1, tick - 3, EventKind::enemy_fell, 99, 1, 57});
  s.events.push_back({2, tick - 1, EventKind::purchase, 1, 'm', 35});
  return s;
}

// Moves every ball as the server would between two snapshots dt_s apart.
inline Snapshot advance(Snapshot s, std::uint32_t ticks, double dt_s) {
  s.tick += ticks;
  for (auto& b : s.balls) {
    b.x += b.vx * dt_s;
    b.y += b.vy * dt_s;
    b.vx *= 0.98;
    b.vy *= 0.97;
  }
  return s;
}

inline std::vector<Message> all_messages() {
  SnapshotMsg full;
  full.tick = 42;
  full.phase = Phase::shop;
  full.level = 3;
  full.deadline_tick = 3042;  // the shop closes in 30 s
  full.balls.push_back({7, true, 800, 2400, -16, 32, 256, 640, BallKind::player, 1});
  PlayerEntry p;
  p.id = 1;
  p.name = "ann";
  p.coins = 1'000'000'000'000'000;
  p.lives = 3;
  p.mass = 41;
  p.vmax_u_per_s = 178.5;
  p.accel_u_per_s2 = 210;
  p.multiplier = 1.1220000000000001;
  p.bank = true;
  p.weapon = Weapon::rockets;
  p.prices = std::array<std::int64_t, 7>{36, 120, 180, 1'000'000, 550, 150, 500};
  p.ready = true;
  p.alive = false;
  full.players.push_back(p);
  full.events.push_back({7, 40, EventKind::purchase, 1, 'm', 35});
  SnapshotMsg delta;
  delta.tick = 50;
  delta.base = 42;
  delta.part = 1;
  delta.parts = 2;
  delta.phase = Phase::play;
  delta.level = 4;
  delta.balls.push_back({7, false, 3, -4, 0, 1, 0, 0, BallKind::enemy, 0});
  delta.gone = {9, 10};
  PlayerEntry pd;
  pd.id = 1;
  pd.coins = 99;
  delta.players.push_back(pd);
  delta.left = {2};
  return {
      Hello{"ann", "", "", "....", "0123456789abcdef"},
      Hello{"bob", std::string(96, 'a'), std::string(48, '0'), "", "fedcba9876543210", "", "", std::string(64, 'c')},
      Challenge{"00000000000003e8" + std::string(32, 'f'), std::string(64, 'd')},
      [] {
        Welcome w{3, std::string(32, 'b'), 20, 8, 10000, 60000, 8, 12345, true};
        w.match.frame_s = 0.02;  // a tuned host's physics and shop (issue 36)
        w.match.multiplier_upgrade_factor = 1.25;
        w.match.bank_interest_factor = 1.2;
        w.match.model = fts::sim::Model::discrete;
        w.match.substeps = 4;
        w.match.friction_per_frame = 0.95;
        w.match.friction_cutoff_u_per_s = 0;
        w.match.arena_width_u = 640.5;
        return w;
      }(),
      Error{"version", "protocol version 2 is not supported; this server speaks version 1"},
      Input{41, {{10, -1, 1, false}, {9, 0, 0, true}}},
      Command{1, CommandOp::buy, 'm', {}, {}},
      Command{2, CommandOp::ready, 0, {}, {}},
      Command{3, CommandOp::play_again, 0, {}, {}},
      Command{4, CommandOp::chat, 0, "gg", {}},
      Result{1, 1, true, "ok", "bought mass"},
      Result{2, 4, false, "coins", "needs 35 coins, you have 12"},
      Ping{},
      Bye{"quit"},
      Chat{1, 2, "bob", "gg"},
      Chat{2, 0, "host", "bye"},
      Leaderboard{5, {{1, "ann", 12, 4500}, {2, "bob", 12, 900}, {3, "?x?", 3, 0}}, 3, 2, 12, 900},
      Leaderboard{6, {}, 0, 0, 0, 0},
      Moved{"10.0.0.7:7778", "KWZWC"},
      full,
      delta,
  };
}

}  // namespace fts::protocol::test
