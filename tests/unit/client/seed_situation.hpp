// The seed's shop slide: level 3 complete, 286 coins, 1 life, multiplier 1.06, no bank.
#pragma once

#include <cstdint>

#include "fts/protocol/snapshot.hpp"
#include "ui/render.hpp"

namespace fts::client::test {

inline protocol::PlayerState seed_player() {
  protocol::PlayerState p;
  p.id = 1;
  p.name = "ann";
  p.coins = 286;
  p.lives = 1;
  p.mass = 40;
  p.vmax_u_per_s = 170;
  p.accel_u_per_s2 = 200;
  p.multiplier = 1.061208;  // 1.02^3
  p.prices = {35, 100, 150, 1'000'000, 522, 100, 500};
  p.alive = true;
  return p;
}

// The view of player 1 on a terminal without colour.
inline ViewState plain_view() {
  ViewState v;
  v.my_player_id = 1;
  v.color = false;
  return v;
}

// A ball of a snapshot for the renderer's tests: its mass and radius as given.
inline protocol::BallState make_ball(std::uint32_t id, double x, double y, protocol::BallKind kind,
                                     std::uint32_t owner, double mass, double radius) {
  protocol::BallState b;
  b.id = id;
  b.x = x;
  b.y = y;
  b.kind = kind;
  b.owner = owner;
  b.mass = mass;
  b.radius = radius;
  return b;
}

inline protocol::Snapshot seed_snapshot(protocol::Phase phase) {
  protocol::Snapshot s;
  s.tick = 1000;
  s.phase = phase;
  s.level = 3;
  s.players.push_back(seed_player());
  return s;
}

}  // namespace fts::client::test
