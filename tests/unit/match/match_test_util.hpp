// Helpers for match tests: a started match, hand-placed balls, idle ticks.
#pragma once

#include <string>
#include <vector>

#include "fts/sim/match.hpp"

namespace fts::test {

using namespace fts::sim;

inline TickInputs joins(int players) {
  TickInputs in;
  for (int i = 1; i <= players; ++i) in.joins.push_back({static_cast<PlayerId>(i), "p" + std::to_string(i)});
  return in;
}

inline TickInputs all_ready(const MatchState& s) {
  TickInputs in;
  for (const Player& p : s.players) in.players.push_back({p.id, {}, {{CommandKind::ready, {}}}});
  return in;
}

// A match in the playing phase of level 1 with `players` players (ids 1..n).
inline MatchState started(int players, std::uint64_t seed = 1, MatchConfig cfg = {}) {
  MatchState s = make_match(cfg, seed);
  step(s, joins(players));
  step(s, all_ready(s));
  return s;
}

inline void remove_enemies(MatchState& s) {
  std::vector<BallId> gone;
  for (const auto& [id, b] : s.bodies)
    if (b.kind == BodyKind::enemy) gone.push_back(id);
  for (BallId id : gone) {
    s.bodies.erase(id);
    auto& v = s.world.balls;
    for (auto it = v.begin(); it != v.end(); ++it)
      if (it->id == id) { v.erase(it); break; }
  }
}

// A still enemy (no AI thrust) at pos; returns its id.
inline BallId add_enemy(MatchState& s, Vec2 pos, Vec2 vel = {}, double mass = 30.0) {
  Ball b;
  b.id = s.next_ball_id++;
  b.pos = pos;
  b.vel = vel;
  b.mass = mass;
  b.radius = radius_for_mass(s.cfg, mass);
  s.world.balls.push_back(b);
  Body body;
  body.kind = BodyKind::enemy;
  body.spec.mass = mass;
  body.spec.radius_u = b.radius;
  body.spec.role = EnemyRole::still;
  s.bodies[b.id] = body;
  return b.id;
}

inline Ball& ball_of(MatchState& s, PlayerId p) { return *find_ball(s.world, find_player(s, p)->ball); }

inline std::vector<Event> run(MatchState& s, int ticks, const TickInputs& in = {}) {
  std::vector<Event> all;
  for (int i = 0; i < ticks; ++i) {
    auto ev = step(s, in).events;
    all.insert(all.end(), ev.begin(), ev.end());
  }
  return all;
}

// The events of one kind, as their records.
template <class Kind>
std::vector<Kind> of(const std::vector<Event>& ev) {
  std::vector<Kind> out;
  for (const auto& e : ev)
    if (const Kind* k = std::get_if<Kind>(&e)) out.push_back(*k);
  return out;
}

// Whether `p` fell in `ev`.
inline bool fell(const std::vector<Event>& ev, PlayerId p) {
  for (const auto& f : of<PlayerFell>(ev))
    if (f.player == p) return true;
  return false;
}

// The defeat of `enemy` in `ev`, or null.
inline const EnemyDefeated* defeat_of(const std::vector<Event>& ev, BallId enemy) {
  for (const auto& e : ev)
    if (const auto* d = std::get_if<EnemyDefeated>(&e); d && d->enemy == enemy) return d;
  return nullptr;
}

inline Command buy(std::string item) { return {CommandKind::buy, std::move(item)}; }

}  // namespace fts::test
