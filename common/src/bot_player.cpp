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
void stay_on_platform(PlayerTick& t, const Ball& me, double accel, double width_u, double height_u) {
  const double margin = 12.0;
  auto axis = [&](double pos, double vel, double hi, std::int8_t& cmd) {
    const double stop = pos + vel * std::fabs(vel) / (2.0 * accel);  // ignoring friction: safe side
    if (stop < margin || pos < margin) cmd = 1;
    else if (stop > hi - margin || pos > hi - margin) cmd = -1;
  };
  axis(me.pos.x, me.vel.x, width_u, t.input.move_x);
  axis(me.pos.y, me.vel.y, height_u, t.input.move_y);
}

void shop(const MatchState& s, const Player& p, PlayerTick& t) {
  const Economy& e = p.eco;
  ShopSight sight;
  sight.coins = e.coins;
  sight.lives = e.lives;
  sight.bank = e.bank;
  sight.accel_u_per_s2 = e.accel_u_per_s2;
  sight.vmax_u_per_s = e.vmax_u_per_s;
  sight.mass = e.mass;
  for (const ItemDef& d : item_table()) sight.prices[index_of(d.item)] = price_of(e, d.item);
  sight.start_accel_u_per_s2 = s.cfg.player_accel_u_per_s2;
  sight.start_vmax_u_per_s = s.cfg.player_vmax_u_per_s;
  sight.start_mass = s.cfg.player_mass;
  const auto want = bot_shop_choice(sight);
  if (want && !p.ready) t.commands.push_back({CommandKind::buy, std::string(to_string(*want))});
  else if (!p.ready) t.commands.push_back({CommandKind::ready, {}});
}

void play(const MatchState& s, const Player& p, PlayerTick& t) {
  const Ball* me = p.ball ? find_ball(s.world, p.ball) : nullptr;
  if (!me) return;
  BotSight sight;
  sight.me = *me;
  for (const Ball& b : s.world.balls) {
    auto it = s.bodies.find(b.id);
    if (it != s.bodies.end() && it->second.kind == BodyKind::enemy) sight.enemies.push_back(b);
  }
  sight.vmax_u_per_s = p.eco.vmax_u_per_s;
  sight.accel_u_per_s2 = p.eco.accel_u_per_s2;
  sight.rockets = p.eco.rockets;
  sight.arena_width_u = s.cfg.arena_width_u;
  sight.arena_height_u = s.cfg.arena_height_u;
  t.input = bot_play_input(sight);
}

}  // namespace

PlayerInput bot_play_input(const BotSight& sight) {
  PlayerTick t;
  const Ball* me = &sight.me;
  const Ball* target = nullptr;
  double best = std::numeric_limits<double>::infinity();
  for (const Ball& b : sight.enemies) {
    const double d = length_sq(b.pos - me->pos);
    if (d < best) {
      best = d;
      target = &b;
    }
  }
  const double vmax = sight.vmax_u_per_s;
  const double w = sight.arena_width_u, h = sight.arena_height_u;
  if (!target) {
    steer(t, me->vel, clamp_len((Vec2{w / 2, h / 2} - me->pos) * 2.0, vmax));
  } else {
    // Push toward the enemy's nearest edge.
    const Vec2 e = target->pos;
    const double dl = e.x, dr = w - e.x, db = e.y, dt = h - e.y;
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
        // The waypoint lies past the switch line (along > reach / 2): reaching it always
        // hands over to the approach, never parks the bot on the boundary.
        goal = e + perp * (s_sign * (reach + 20.0)) - n * reach;
      }
      steer(t, me->vel, clamp_len((goal - me->pos) * 3.0, vmax));
    }
    if (sight.rockets && length_sq(rel) < 150.0 * 150.0) t.input.fire = true;
  }
  stay_on_platform(t, *me, sight.accel_u_per_s2, w, h);
  return t.input;
}

std::optional<Item> bot_shop_choice(const ShopSight& s) {
  auto affordable = [&](Item it) { return s.coins >= s.prices[index_of(it)]; };
  if (s.lives < 2 && affordable(Item::life)) return Item::life;
  if (!s.bank && affordable(Item::bank)) return Item::bank;
  if (s.accel_u_per_s2 < 2.0 * s.start_accel_u_per_s2 && affordable(Item::accel)) return Item::accel;
  if (s.vmax_u_per_s < 1.5 * s.start_vmax_u_per_s && affordable(Item::speed)) return Item::speed;
  if (s.mass < 3 * s.start_mass && affordable(Item::mass)) return Item::mass;
  return std::nullopt;
}

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
