// The playing phase's tick: respawns, thrust, rockets, enemy AI, physics (with friction),
// credit for contacts, falls, and the level's end (complete, restart or game over).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "match_internal.hpp"

namespace fts::sim::detail {
namespace {

int clamp_dir(std::int8_t v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

void fire_rocket(MatchState& s, Player& p, std::vector<Event>& out) {
  const Ball* b = find_ball(s.world, p.ball);
  if (!b) return;
  Vec2 dir = p.aim;
  const double speed = length(b->vel);
  if (speed > 1e-9) dir = b->vel * (1.0 / speed);
  const MatchConfig& cfg = s.cfg;
  const Vec2 pos = b->pos + dir * (b->radius + cfg.rocket_radius_u + 0.5);
  const Vec2 vel = dir * (cfg.rocket_speed_factor * p.eco.vmax_u_per_s);
  Body rb;
  rb.kind = BodyKind::rocket;
  rb.owner = p.id;
  rb.expires_tick = s.tick + ticks_for(cfg, cfg.rocket_lifetime_s);
  const BallId id = add_ball(s, pos, vel, cfg.rocket_radius_u, cfg.rocket_mass, rb);
  p.next_fire_tick = s.tick + ticks_for(cfg, cfg.rocket_cooldown_s);
  out.push_back(RocketFired{p.id, id});
}

void apply_player_inputs(MatchState& s, const std::vector<PlayerTick>& inputs, std::vector<Event>& out) {
  const double dt = s.step_k.dt_s;
  for (const PlayerTick& t : inputs) {
    Player* p = find_player(s, t.player);
    if (!p || !p->ball) continue;
    Ball* b = find_ball(s.world, p->ball);
    if (!b) continue;
    const int dx = clamp_dir(t.input.move_x), dy = clamp_dir(t.input.move_y);
    const bool fires = t.input.fire && p->eco.rockets && s.tick >= p->next_fire_tick;
    // Spawn protection ends when the player acts: a protected ball never moves itself,
    // so it cannot push anything (README, "Where the rules left room").
    if (dx != 0 || dy != 0 || fires) p->protected_until_tick = -1;
    apply_thrust(*b, dx, dy, p->eco.accel_u_per_s2, p->eco.vmax_u_per_s, dt);
    if (dx != 0 || dy != 0) {
      const double k = (dx != 0 && dy != 0) ? std::sqrt(0.5) : 1.0;
      p->aim = {dx * k, dy * k};
    }
    if (fires) fire_rocket(s, *p, out);
  }
}

// The player a contact with this ball credits: its owner, except a ball under spawn
// protection, which credits nobody (what an enemy reflects off a fixed ball is no hit).
PlayerId toucher(const MatchState& s, const Body& b) {
  if (b.kind == BodyKind::rocket) return b.owner;
  if (b.kind != BodyKind::player) return 0;
  const Player* p = find_player(s, b.owner);
  return p && p->protected_at(s.tick) ? PlayerId{0} : b.owner;
}

// Last-touch credit: a player's (or its rocket's) hit marks the enemy; enemy-on-enemy
// contacts pass on the more recent mark if its originating hit is within the chain window.
void credit_contacts(MatchState& s, const StepReport& report) {
  const std::int64_t now = s.tick;
  const std::int64_t window = ticks_for(s.cfg, s.cfg.credit_chain_s);
  for (const Contact& c : report.contacts) {
    auto ia = s.bodies.find(c.a), ib = s.bodies.find(c.b);
    if (ia == s.bodies.end() || ib == s.bodies.end()) continue;
    Body& a = ia->second;
    Body& b = ib->second;
    const bool ea = a.kind == BodyKind::enemy, eb = b.kind == BodyKind::enemy;
    if (ea && eb) {
      const PlayerId ca = a.credit, cb = b.credit;
      const std::int64_t ta = a.credit_tick, tb = b.credit_tick;
      if (cb && now - tb <= window && (!ca || tb > ta)) { a.credit = cb; a.credit_tick = tb; }
      if (ca && now - ta <= window && (!cb || ta > tb)) { b.credit = ca; b.credit_tick = ta; }
    } else if (const PlayerId by = ea ? toucher(s, b) : PlayerId{0}; by) {
      a.credit = by;
      a.credit_tick = now;
    } else if (const PlayerId by_a = eb ? toucher(s, a) : PlayerId{0}; by_a) {
      b.credit = by_a;
      b.credit_tick = now;
    }
  }
}

void handle_falls(MatchState& s, const StepReport& report, std::vector<Event>& out) {
  for (BallId id : report.fallen) {
    auto it = s.bodies.find(id);
    if (it == s.bodies.end()) continue;
    const Body body = it->second;
    s.bodies.erase(it);
    if (body.kind == BodyKind::enemy) {
      EnemyDefeated e;
      e.enemy = id;
      e.level = s.level;
      if (Player* p = body.credit ? find_player(s, body.credit) : nullptr) {
        const Coins reward = defeat_reward(body.spec.mass, p->eco.multiplier, s.level,
                                           is_boss_level(s.level, s.cfg), s.cfg);
        e.player = p->id;
        e.coins = earn_defeat(p->eco, reward, s.cfg);
      }
      out.push_back(e);
    } else if (body.kind == BodyKind::player) {
      Player* p = find_player(s, body.owner);
      if (!p) continue;
      p->ball = 0;
      p->eco.lives = std::max<std::int64_t>(0, p->eco.lives - 1);
      if (p->in_match()) p->respawn_tick = s.tick + ticks_for(s.cfg, s.cfg.respawn_delay_s);
      out.push_back(PlayerFell{p->id, id, s.level, p->eco.lives});
    }
  }
}

void expire_rockets(MatchState& s) {
  std::vector<BallId> gone;
  for (const auto& [id, b] : s.bodies)
    if (b.kind == BodyKind::rocket && s.tick >= b.expires_tick) gone.push_back(id);
  for (BallId id : gone) remove_ball(s, id);
}

void check_level_end(MatchState& s, std::vector<Event>& out) {
  bool anyone = false, active = false, on_platform = false, enemies = false;
  for (const Player& p : s.players) {
    anyone = anyone || p.in_match();
    active = active || (p.in_match() && !p.parked);
    on_platform = on_platform || p.ball != 0;
  }
  for (const auto& [id, b] : s.bodies) enemies = enemies || b.kind == BodyKind::enemy;
  if (!anyone) {
    s.phase = Phase::game_over;
    out.push_back(GameOver{s.level});
  } else if (!active) {
    // Everyone still in the match quit: the level waits for one of them to come back.
  } else if (!enemies) {
    for (Player& p : s.players) {
      p.ready = false;
      if (!p.in_match()) continue;
      const Coins before = p.eco.coins;
      complete_level(p.eco, s.cfg);
      if (p.eco.coins != before) out.push_back(InterestPaid{p.id, p.eco.coins - before});
    }
    ++s.levels_cleared;
    s.phase = Phase::shop;
    s.shop_deadline_tick = s.tick + ticks_for(s.cfg, s.cfg.shop_timeout_s);
    out.push_back(LevelComplete{s.level});
  } else if (!on_platform) {
    start_level(s, s.level, true, out);
  }
}

}  // namespace

void play_tick(MatchState& s, const std::vector<PlayerTick>& inputs, std::vector<Event>& out) {
  for (Player& p : s.players) {
    if (p.protected_until_tick >= 0 && !p.protected_at(s.tick)) p.protected_until_tick = -1;  // ran out
    if (p.in_match() && !p.ball && p.respawn_tick >= 0 && s.tick >= p.respawn_tick) respawn_player(s, p, out);
  }
  apply_player_inputs(s, inputs, out);
  steer_enemies(s);
  StepReport report;
  // A protected ball is immovable for the step: infinite mass in the world (every model
  // takes its limit), its own mass back afterwards, so that the state between ticks (the
  // hash, checkpoints, snapshots) only ever holds finite masses.
  std::vector<std::pair<BallId, double>> fixed;  // allocates only while someone is protected
  for (const Player& p : s.players) {
    if (!p.ball || !p.protected_at(s.tick)) continue;
    if (Ball* b = find_ball(s.world, p.ball)) {
      fixed.emplace_back(b->id, b->mass);
      b->mass = std::numeric_limits<double>::infinity();
    }
  }
  fts::sim::step(s.world, s.physics, s.step_k, report);  // moves, collides, applies friction
  for (const auto& [id, mass] : fixed)
    if (Ball* b = find_ball(s.world, id)) b->mass = mass;
  credit_contacts(s, report);
  handle_falls(s, report, out);
  expire_rockets(s);
  check_level_end(s, out);
}

}  // namespace fts::sim::detail
