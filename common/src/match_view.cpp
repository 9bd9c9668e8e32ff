#include "fts/sim/match_view.hpp"

#include <algorithm>

namespace fts::sim {

MatchView make_view(const MatchState& s) {
  MatchView v;
  v.tick = s.tick;
  v.phase = s.phase;
  v.level = s.level;
  v.levels_cleared = s.levels_cleared;
  if (s.phase == Phase::shop) v.shop_ticks_left = std::max<std::int64_t>(0, s.shop_deadline_tick - s.tick);
  if (s.phase == Phase::shop) v.deadline_tick = s.shop_deadline_tick;
  if (s.phase == Phase::lobby) v.deadline_tick = s.lobby_deadline_tick;
  for (const Player& p : s.players) {
    PlayerView pv;
    pv.id = p.id;
    pv.name = p.name;
    const Economy& e = p.eco;
    pv.coins = e.coins;
    pv.lives = e.lives;
    for (const ItemDef& d : item_table()) pv.prices[index_of(d.item)] = price_of(e, d.item);
    pv.mass = e.mass;
    pv.vmax_u_per_s = e.vmax_u_per_s;
    pv.accel_u_per_s2 = e.accel_u_per_s2;
    pv.multiplier = e.multiplier;
    pv.bank = e.bank;
    pv.rockets = e.rockets;
    pv.ready = p.ready;
    pv.alive = p.ball != 0;
    pv.out = !p.in_match();
    pv.away = !p.connected || p.parked;
    pv.ball = p.ball;
    pv.protected_until_tick = p.protected_at(s.tick) ? p.protected_until_tick : -1;
    pv.purchases = e.purchases;
    pv.defeats = e.defeats;
    v.players.push_back(std::move(pv));
  }
  for (const Ball& b : s.world.balls) {
    BallView bv;
    bv.id = b.id;
    if (auto it = s.bodies.find(b.id); it != s.bodies.end()) {
      bv.kind = it->second.kind;
      bv.owner = it->second.owner;
    }
    bv.x = b.pos.x;
    bv.y = b.pos.y;
    bv.vx = b.vel.x;
    bv.vy = b.vel.y;
    bv.radius = b.radius;
    bv.mass = b.mass;
    v.balls.push_back(bv);
  }
  return v;
}

}  // namespace fts::sim
