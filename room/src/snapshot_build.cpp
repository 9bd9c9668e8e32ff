#include "fts/room/snapshot_build.hpp"

#include <optional>

namespace fts::room {
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
  using Wire = std::optional<protocol::Event>;
  const std::uint32_t t = u32(tick);
  for (const sim::Event& e : events) {
    const Wire w = std::visit(
        sim::Overloaded{
            [&](const sim::Joined& x) -> Wire { return protocol::Event{0, t, K::player_joined, x.player.value, 0, 0}; },
            [&](const sim::JoinRefused&) -> Wire { return std::nullopt; },
            [&](const sim::Left& x) -> Wire { return protocol::Event{0, t, K::player_left, x.player.value, 0, 0}; },
            [&](const sim::LevelStarted& x) -> Wire {
              return protocol::Event{0, t, x.restart ? K::level_restarted : K::level_started, 0, 0, x.level};
            },
            [&](const sim::EnemyDefeated& x) -> Wire { return protocol::Event{0, t, K::enemy_fell, x.enemy.value, x.player.value, x.coins}; },
            [&](const sim::PlayerFell& x) -> Wire { return protocol::Event{0, t, K::player_fell, x.player.value, x.ball.value, x.lives_left}; },
            [&](const sim::PlayerRespawned& x) -> Wire { return protocol::Event{0, t, K::respawned, x.player.value, x.ball.value, 0}; },
            [&](const sim::LevelComplete& x) -> Wire { return protocol::Event{0, t, K::level_complete, 0, 0, x.level}; },
            [&](const sim::Purchased& x) -> Wire {
              if (!x.ok) return std::nullopt;  // refusals go to the buyer only, as a command result
              return protocol::Event{0, t, K::purchase, x.player.value, static_cast<std::uint32_t>(sim::shop_key(x.item)), x.price};
            },
            [&](const sim::RocketFired& x) -> Wire { return protocol::Event{0, t, K::rocket_fired, x.player.value, x.rocket.value, 0}; },
            [&](const sim::GameOver& x) -> Wire { return protocol::Event{0, t, K::match_over, 0, 0, x.level}; },
            [&](const sim::InterestPaid& x) -> Wire { return protocol::Event{0, t, K::interest, x.player.value, 0, x.coins}; },
        },
        e);
    if (w) out.push_back(*w);
  }
}

protocol::Snapshot build_snapshot(const sim::MatchView& view, const std::deque<protocol::Event>& recent) {
  protocol::Snapshot s;
  s.tick = u32(view.tick);
  s.phase = wire_phase(view.phase);
  s.level = u32(view.level);
  s.deadline_tick = view.deadline_tick > 0 ? u32(view.deadline_tick) : 0;
  s.balls.reserve(view.balls.size());
  for (const auto& b : view.balls) {
    s.balls.push_back({b.id.value, b.x, b.y, b.vx, b.vy, b.radius, b.mass, wire_kind(b.kind), b.owner.value});
  }
  for (const auto& p : view.players) {
    protocol::PlayerState w;
    w.id = p.id.value;
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
    w.protected_until_tick = p.protected_until_tick > 0 ? u32(p.protected_until_tick) : 0;
    w.away = p.away;
    s.players.push_back(std::move(w));
  }
  s.events.assign(recent.begin(), recent.end());
  return s;
}

}  // namespace fts::room
