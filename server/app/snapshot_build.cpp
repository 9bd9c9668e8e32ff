#include "app/snapshot_build.hpp"

namespace fts::server {
namespace {

protocol::Phase wire_phase(sim::Phase p) {
  switch (p) {
    case sim::Phase::lobby: return protocol::Phase::lobby;
    case sim::Phase::playing: return protocol::Phase::play;
    case sim::Phase::shop: return protocol::Phase::shop;
    case sim::Phase::game_over: return protocol::Phase::over;
  }
  return protocol::Phase::lobby;
}

protocol::BallKind wire_kind(sim::BodyKind k) {
  switch (k) {
    case sim::BodyKind::enemy: return protocol::BallKind::enemy;
    case sim::BodyKind::player: return protocol::BallKind::player;
    case sim::BodyKind::rocket: return protocol::BallKind::rocket;
  }
  return protocol::BallKind::enemy;
}

std::uint32_t u32(std::int64_t v) { return v < 0 ? 0u : v > 0xffffffffll ? 0xffffffffu : static_cast<std::uint32_t>(v); }

}  // namespace

void append_wire_events(std::int64_t tick, const std::vector<sim::Event>& events, std::vector<protocol::Event>& out) {
  using K = protocol::EventKind;
  for (const sim::Event& e : events) {
    protocol::Event w;
    w.tick = u32(tick);
    switch (e.kind) {
      case sim::EventKind::joined: w = {w.tick, K::player_joined, e.player, 0, 0}; break;
      case sim::EventKind::left: w = {w.tick, K::player_left, e.player, 0, 0}; break;
      case sim::EventKind::level_started:
        w = {w.tick, e.restart ? K::level_restarted : K::level_started, 0, 0, e.level};
        break;
      case sim::EventKind::enemy_defeated: w = {w.tick, K::enemy_fell, e.ball, e.player, e.coins}; break;
      case sim::EventKind::player_fell: w = {w.tick, K::player_fell, e.player, e.ball, e.lives_left}; break;
      case sim::EventKind::player_respawned: w = {w.tick, K::respawned, e.player, e.ball, 0}; break;
      case sim::EventKind::level_complete: w = {w.tick, K::level_complete, 0, 0, e.level}; break;
      case sim::EventKind::purchase:
        if (!e.ok) continue;  // refusals go to the buyer only, as a command result
        w = {w.tick, K::purchase, e.player, static_cast<std::uint32_t>(sim::shop_key(e.item)), e.price};
        break;
      case sim::EventKind::rocket_fired: w = {w.tick, K::rocket_fired, e.player, e.ball, 0}; break;
      case sim::EventKind::game_over: w = {w.tick, K::match_over, 0, 0, e.level}; break;
      case sim::EventKind::interest: w = {w.tick, K::interest, e.player, 0, e.coins}; break;
      case sim::EventKind::join_refused: continue;
    }
    out.push_back(w);
  }
}

protocol::Snapshot build_snapshot(const sim::MatchView& view, const std::deque<protocol::Event>& recent) {
  protocol::Snapshot s;
  s.tick = u32(view.tick);
  s.phase = wire_phase(view.phase);
  s.level = u32(view.level);
  s.balls.reserve(view.balls.size());
  for (const auto& b : view.balls) {
    s.balls.push_back({b.id, b.x, b.y, b.vx, b.vy, b.radius, b.mass, wire_kind(b.kind), b.owner});
  }
  for (const auto& p : view.players) {
    protocol::PlayerState w;
    w.id = p.id;
    w.name = p.name;
    w.coins = p.coins;
    w.lives = static_cast<std::int32_t>(p.lives > 0x7fffffff ? 0x7fffffff : p.lives);
    w.mass = static_cast<double>(p.mass);
    w.vmax_u_per_s = p.vmax_u_per_s;
    w.accel_u_per_s2 = p.accel_u_per_s2;
    w.multiplier = p.multiplier;
    w.bank = p.bank;
    w.weapon = p.rockets ? protocol::Weapon::rockets : protocol::Weapon::none;
    w.prices = p.prices;
    w.ready = p.ready;
    w.alive = p.alive;
    s.players.push_back(std::move(w));
  }
  s.events.assign(recent.begin(), recent.end());
  return s;
}

}  // namespace fts::server
