// Levels inside a match: clearing the platform, placing players and enemies, respawns.
#include <algorithm>
#include <optional>

#include "match_internal.hpp"

namespace fts::sim::detail {
namespace {

// Spawn point `slot` of `count`: spread along the left third, vertical centre for one.
Vec2 spawn_slot(const MatchConfig& cfg, std::int64_t slot, std::int64_t count) {
  const double x = cfg.arena_width_u * cfg.player_spawn_x_fraction;
  const double y = cfg.arena_height_u * static_cast<double>(slot + 1) / static_cast<double>(count + 1);
  return {x, y};
}

std::int64_t players_in_match(const MatchState& s) {
  return std::count_if(s.players.begin(), s.players.end(), [](const Player& p) { return p.in_match(); });
}

std::int64_t slot_of(const MatchState& s, PlayerId id) {
  std::int64_t i = 0;
  for (const Player& p : s.players) {
    if (p.id == id) return i;
    if (p.in_match()) ++i;
  }
  return i;
}

BallId place_player(MatchState& s, Player& p, Vec2 pos) {
  Body b;
  b.kind = BodyKind::player;
  b.owner = p.id;
  const double mass = static_cast<double>(p.eco.mass);
  p.ball = add_ball(s, pos, {}, radius_for_mass(s.cfg, mass), mass, b);
  p.respawn_tick = -1;
  return p.ball;
}

// Spawn protection (docs/rules.md) from this tick on, when the match has it.
void protect(const MatchState& s, Player& p) {
  if (s.cfg.spawn_protection_s > 0.0) p.protected_until_tick = s.tick + ticks_for(s.cfg, s.cfg.spawn_protection_s);
}

}  // namespace

BallId add_ball(MatchState& s, Vec2 pos, Vec2 vel, double radius, double mass, const Body& body) {
  Ball b;
  b.id = BallId{s.next_ball_id++};
  b.pos = pos;
  b.vel = vel;
  b.radius = radius;
  b.mass = mass;
  s.world.balls.push_back(b);
  s.bodies[b.id] = body;
  return b.id;
}

void remove_ball(MatchState& s, BallId id) {
  auto& balls = s.world.balls;
  auto it = std::lower_bound(balls.begin(), balls.end(), id, [](const Ball& b, BallId v) { return b.id < v; });
  if (it != balls.end() && it->id == id) balls.erase(it);
  auto body = s.bodies.find(id);
  if (body == s.bodies.end()) return;
  if (body->second.kind == BodyKind::player) {
    if (Player* p = find_player(s, body->second.owner); p && p->ball == id) {
      p->ball = 0;
      p->protected_until_tick = -1;  // the protection is the ball's
    }
  }
  s.bodies.erase(body);
}

void start_level(MatchState& s, std::int64_t level, bool restart, std::vector<Event>& out) {
  while (!s.world.balls.empty()) remove_ball(s, s.world.balls.back().id);
  s.level = level;
  s.phase = Phase::playing;
  const std::int64_t k = players_in_match(s);
  std::int64_t slot = 0;
  for (Player& p : s.players) {
    p.ready = false;
    p.ball = 0;
    p.respawn_tick = -1;
    p.protected_until_tick = -1;
    p.next_fire_tick = s.tick;
    if (!p.in_match() || p.parked) continue;
    place_player(s, p, spawn_slot(s.cfg, slot++, k));
    protect(s, p);  // every start, a restart included: a player who has not acted yet is not knocked off
  }
  const std::int64_t n = enemy_count_for_players(level, k, s.cfg);
  const Box box = enemy_spawn_box(s.cfg);
  for (std::int64_t i = 0; i < n; ++i) {
    Body b;
    b.kind = BodyKind::enemy;
    b.index = i;
    b.spec = enemy_spec(level, i, s.rng, s.cfg);
    Vec2 pos;
    if (level == 1 && i == 0) pos = {s.cfg.arena_width_u * 0.5, s.cfg.arena_height_u * 0.5};
    else pos = find_spawn(s.world.balls, b.spec.radius_u, box, s.rng, s.cfg);
    if (b.spec.role != EnemyRole::still) b.goal = draw_goal(level, s.rng, s.cfg);
    add_ball(s, pos, {}, b.spec.radius_u, b.spec.mass, b);
  }
  out.push_back(LevelStarted{level, restart});
}

void start_new_match(MatchState& s, std::vector<Event>& out) {
  for (Player& p : s.players) {
    p.eco = start_economy(s.cfg);
    p.ready = false;
  }
  s.levels_cleared = 0;
  s.lobby_deadline_tick = -1;
  ++s.matches_started;
  start_level(s, 1, false, out);
}

void respawn_player(MatchState& s, Player& p, std::vector<Event>& out) {
  const double mass = static_cast<double>(p.eco.mass);
  const double r = radius_for_mass(s.cfg, mass);
  const std::int64_t k = std::max<std::int64_t>(1, players_in_match(s));
  const std::int64_t own = std::min(slot_of(s, p.id), k - 1);
  std::optional<Vec2> pos;
  for (std::int64_t i = 0; i < k && !pos; ++i) {
    const Vec2 c = spawn_slot(s.cfg, (own + i) % k, k);
    if (is_free(s.world.balls, c, r, s.cfg.spawn_gap_u)) pos = c;
  }
  if (!pos) {
    const double x1 = s.cfg.arena_width_u / 3.0;
    const Box left{std::min(r, x1 * 0.5), std::min(r, s.cfg.arena_height_u * 0.5), std::max(x1 - r, x1 * 0.5),
                   std::max(s.cfg.arena_height_u - r, s.cfg.arena_height_u * 0.5)};
    pos = find_spawn(s.world.balls, r, left, s.rng, s.cfg);
  }
  place_player(s, p, *pos);
  protect(s, p);
  out.push_back(PlayerRespawned{p.id, p.ball});
}

}  // namespace fts::sim::detail
