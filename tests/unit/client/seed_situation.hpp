// The seed's shop slide: level 3 complete, 286 coins, 1 life, multiplier 1.06, no bank.
#pragma once

#include "fts/protocol/snapshot.hpp"

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

inline protocol::Snapshot seed_snapshot(protocol::Phase phase) {
  protocol::Snapshot s;
  s.tick = 1000;
  s.phase = phase;
  s.level = 3;
  s.players.push_back(seed_player());
  return s;
}

}  // namespace fts::client::test
