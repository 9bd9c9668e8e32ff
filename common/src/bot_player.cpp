#include "fts/sim/bot_player.hpp"

#include <cmath>
#include <limits>

namespace fts::sim {
namespace {

std::int8_t sign_with_deadband(double v, double band) {
  return v > band ? 1 : (v < -band ? -1 : 0);
}

// Thrust that brings velocity v toward desired velocity vd on each axis.
void steer(PlayerTick& t, Vec2 v, Vec2 vd) {
  t.input.move_x = sign_with_deadband(vd.x - v.x, 4.0);
  t.input.move_y = sign_with_deadband(vd.y - v.y, 4.0);
}

Vec2 clamp_len(Vec2 v, double max_len) {
  const double l = length(v);
  return l > max_len && l > 0.0 ? v * (max_len / l) : v;
}

// Overrides thrust on an axis whose current motion would carry the ball past an edge.
void stay_on_platform(PlayerTick& t, const Ball& me, double accel, const MatchConfig& cfg) {
  const double margin = 12.0;
  auto axis = [&](double pos, double vel, double hi, std::int8_t& cmd) {
    const double stop = pos + vel * std::fabs(vel) / (2.0 * accel);  // ignoring friction: safe side
    if (stop < margin || pos < margin) cmd = 1;
    else if (stop > hi - margin || pos > hi - margin) cmd = -1;
  };
  axis(me.pos.x, me.vel.x, cfg.arena_width_u, t.input.move_x);
  axis(me.pos.y, me.vel.y, cfg.arena_height_u, t.input.move_y);
}

void shop(const MatchState& s, const Player& p, PlayerTick& t) {
  const Economy& e = p.eco;
  auto affordable = [&](Item it) { return e.coins >= price_of(e, it); };
  std::optional<Item> want;
  if (e.lives < 2 && affordable(Item::life)) want = Item::life;
  else if (!e.bank && affordable(Item::bank)) want = Item::bank;
  else if (e.accel_u_per_s2 < 2.0 * s.cfg.player_accel_u_per_s2 && affordable(Item::accel)) want = Item::accel;
  else if (e.vmax_u_per_s < 1.5 * s.cfg.player_vmax_u_per_s && affordable(Item::speed)) want = Item::speed;
  else if (e.mass < 3 * s.cfg.player_mass && affordable(Item::mass)) want = Item::mass;
  if (want && !p.ready) t.commands.push_back({CommandKind::buy, std::string(to_string(*want))});
  else if (!p.ready) t.commands.push_back({CommandKind::ready, {}});
}

void play(const MatchState& s, const Player& p, PlayerTick& t) {
  const Ball* me = p.ball ? find_ball(s.world, p.ball) : nullptr;
  if (!me) return;
  const MatchConfig& cfg = s.cfg;
  const Ball* target = nullptr;
  double best = std::numeric_limits<double>::infinity();
  for (const Ball& b : s.world.balls) {
    auto it = s.bodies.find(b.id);
    if (it == s.bodies.end() || it->second.kind != BodyKind::enemy) continue;
    const double d = length_sq(b.pos - me->pos);
    if (d < best) {
      best = d;
      target = &b;
    }
  }
  const double vmax = p.eco.vmax_u_per_s;
  if (!target) {
    steer(t, me->vel, clamp_len((Vec2{cfg.arena_width_u / 2, cfg.arena_height_u / 2} - me->pos) * 2.0, vmax));
  } else {
    // Push toward the enemy's nearest edge.
    const Vec2 e = target->pos;
    const double dl = e.x, dr = cfg.arena_width_u - e.x, db = e.y, dt = cfg.arena_height_u - e.y;
    Vec2 n{-1, 0};
    double m = dl;
    if (dr < m) { m = dr; n = {1, 0}; }
    if (db < m) { m = db; n = {0, -1}; }
    if (dt < m) { m = dt; n = {0, 1}; }
    const double reach = me->radius + target->radius;
    const Vec2 rel = e - me->pos;          // player to enemy
    const double along = dot(rel, n);      // > 0: the player is behind the enemy
    const Vec2 perp{-n.y, n.x};
    const double side = dot(rel, perp);
    if (along > 0.0 && std::fabs(side) < 0.6 * reach) {
      const double l = length(rel);
      steer(t, me->vel, rel * (vmax / (l > 0 ? l : 1.0)));  // charge
    } else {
      Vec2 goal = e - n * (reach + 15.0);
      if (along <= reach * 0.5) {  // on the wrong side: go around the enemy first
        const double s_sign = side >= 0 ? -1.0 : 1.0;  // the side the player is on
        goal = e + perp * (s_sign * (reach + 20.0)) - n * (reach * 0.5);
      }
      steer(t, me->vel, clamp_len((goal - me->pos) * 3.0, vmax));
    }
    if (p.eco.rockets && length_sq(rel) < 150.0 * 150.0) t.input.fire = true;
  }
  stay_on_platform(t, *me, p.eco.accel_u_per_s2, cfg);
}

}  // namespace

PlayerTick bot_tick(const MatchState& s, PlayerId id) {
  PlayerTick t;
  t.player = id;
  const Player* p = find_player(s, id);
  if (!p) return t;
  switch (s.phase) {
    case Phase::lobby:
      if (!p->ready) t.commands.push_back({CommandKind::ready, {}});
      break;
    case Phase::shop:
      if (p->in_match()) shop(s, *p, t);
      break;
    case Phase::playing: play(s, *p, t); break;
    case Phase::game_over: break;
  }
  return t;
}

}  // namespace fts::sim
