#include "host/match_state_json.hpp"

#include <algorithm>

namespace fts::host {
namespace {

using nlohmann::json;

json economy_to_json(const sim::Economy& e) {
  json prices = json::array();
  for (double p : e.prices.by_item) prices.push_back(p);
  return json::array({e.coins, e.lives, e.mass, e.vmax_u_per_s, e.accel_u_per_s2, e.multiplier, e.bank, e.rockets,
                      prices, e.start_coins, e.earned_defeats, e.earned_interest, e.spent, e.purchases, e.defeats});
}

sim::Economy economy_from_json(const json& a) {
  if (!a.is_array() || a.size() != 15) throw std::invalid_argument("eco must be an array of 15 values");
  sim::Economy e;
  e.coins = a[0].get<sim::Coins>();
  e.lives = a[1].get<std::int64_t>();
  e.mass = a[2].get<std::int64_t>();
  e.vmax_u_per_s = a[3].get<double>();
  e.accel_u_per_s2 = a[4].get<double>();
  e.multiplier = a[5].get<double>();
  e.bank = a[6].get<bool>();
  e.rockets = a[7].get<bool>();
  if (!a[8].is_array() || a[8].size() != sim::kItemCount) throw std::invalid_argument("eco prices: wrong count");
  for (std::size_t i = 0; i < sim::kItemCount; ++i) e.prices.by_item[i] = a[8][i].get<double>();
  e.start_coins = a[9].get<sim::Coins>();
  e.earned_defeats = a[10].get<sim::Coins>();
  e.earned_interest = a[11].get<sim::Coins>();
  e.spent = a[12].get<sim::Coins>();
  e.purchases = a[13].get<std::int64_t>();
  e.defeats = a[14].get<std::int64_t>();
  return e;
}

template <class E>
E enum_from(const json& v, E last, const char* what) {
  const auto n = v.get<std::uint64_t>();
  if (n > static_cast<std::uint64_t>(last)) throw std::invalid_argument(std::string(what) + " out of range");
  return static_cast<E>(n);
}

}  // namespace

json match_state_to_json(const sim::MatchState& s) {
  json j;
  j["phase"] = static_cast<int>(s.phase);
  j["tick"] = s.tick;
  j["level"] = s.level;
  j["levels_cleared"] = s.levels_cleared;
  j["shop_deadline_tick"] = s.shop_deadline_tick;
  j["lobby_deadline_tick"] = s.lobby_deadline_tick;
  j["matches_started"] = s.matches_started;
  j["rng"] = s.rng.state();
  j["next_ball_id"] = s.next_ball_id;
  json& players = j["players"] = json::array();
  for (const sim::Player& p : s.players)
    players.push_back({{"id", p.id.value},
                       {"name", p.name},
                       {"eco", economy_to_json(p.eco)},
                       {"ready", p.ready},
                       {"ball", p.ball.value},
                       {"respawn_tick", p.respawn_tick},
                       {"protected_until_tick", p.protected_until_tick},
                       {"next_fire_tick", p.next_fire_tick},
                       {"aim", {p.aim.x, p.aim.y}},
                       {"connected", p.connected},
                       {"parked", p.parked}});
  // Balls and bodies are many: one array each, fields by position.
  json& balls = j["balls"] = json::array();
  for (const sim::Ball& b : s.world.balls)
    balls.push_back({b.id.value, b.pos.x, b.pos.y, b.vel.x, b.vel.y, b.radius, b.mass});
  json& bodies = j["bodies"] = json::array();
  for (const auto& [id, b] : s.bodies)
    bodies.push_back({id.value, static_cast<int>(b.kind), b.owner.value, b.index, b.spec.mass, b.spec.radius_u,
                      b.spec.accel_u_per_s2, b.spec.vmax_u_per_s, static_cast<int>(b.spec.role), b.goal.x, b.goal.y,
                      b.credit.value, b.credit_tick, b.expires_tick});
  return j;
}

std::variant<sim::MatchState, std::string> match_state_from_json(const json& j, sim::MatchState s) {
  const char* field = "checkpoint";
  try {
    if (!j.is_object()) return std::string("checkpoint: not an object");
    field = "phase";
    s.phase = enum_from(j.at("phase"), sim::Phase::game_over, "phase");
    field = "tick";
    s.tick = j.at("tick").get<std::int64_t>();
    field = "level";
    s.level = j.at("level").get<std::int64_t>();
    field = "levels_cleared";
    s.levels_cleared = j.at("levels_cleared").get<std::int64_t>();
    field = "shop_deadline_tick";
    s.shop_deadline_tick = j.at("shop_deadline_tick").get<std::int64_t>();
    field = "lobby_deadline_tick";
    s.lobby_deadline_tick = j.at("lobby_deadline_tick").get<std::int64_t>();
    field = "matches_started";
    s.matches_started = j.at("matches_started").get<std::int64_t>();
    field = "rng";
    s.rng.set_state(j.at("rng").get<std::array<std::uint64_t, 4>>());
    field = "next_ball_id";
    s.next_ball_id = j.at("next_ball_id").get<std::uint32_t>();
    field = "players";
    s.players.clear();
    for (const json& p : j.at("players")) {
      sim::Player pl;
      pl.id = p.at("id").get<std::uint32_t>();
      pl.name = p.at("name").get<std::string>();
      pl.eco = economy_from_json(p.at("eco"));
      pl.ready = p.at("ready").get<bool>();
      pl.ball = p.at("ball").get<std::uint32_t>();
      pl.respawn_tick = p.at("respawn_tick").get<std::int64_t>();
      // Absent in checkpoints written before spawn protection: not protected.
      pl.protected_until_tick = p.value("protected_until_tick", std::int64_t{-1});
      pl.next_fire_tick = p.at("next_fire_tick").get<std::int64_t>();
      const auto aim = p.at("aim").get<std::array<double, 2>>();
      pl.aim = {aim[0], aim[1]};
      pl.connected = p.at("connected").get<bool>();
      pl.parked = p.at("parked").get<bool>();
      if (!s.players.empty() && !(s.players.back().id < pl.id)) return std::string("players: ids not ascending");
      s.players.push_back(std::move(pl));
    }
    field = "balls";
    s.world.balls.clear();
    for (const json& b : j.at("balls")) {
      const auto v = b.get<std::array<double, 7>>();
      sim::Ball ball;
      ball.id = b[0].get<std::uint32_t>();
      ball.pos = {v[1], v[2]};
      ball.vel = {v[3], v[4]};
      ball.radius = v[5];
      ball.mass = v[6];
      if (!s.world.balls.empty() && !(s.world.balls.back().id < ball.id)) return std::string("balls: ids not ascending");
      s.world.balls.push_back(ball);
    }
    field = "bodies";
    s.bodies.clear();
    for (const json& b : j.at("bodies")) {
      if (!b.is_array() || b.size() != 14) return std::string("bodies: each must be an array of 14 values");
      sim::Body body;
      body.kind = enum_from(b[1], sim::BodyKind::rocket, "body kind");
      body.owner = b[2].get<std::uint32_t>();
      body.index = b[3].get<std::int64_t>();
      body.spec.mass = b[4].get<double>();
      body.spec.radius_u = b[5].get<double>();
      body.spec.accel_u_per_s2 = b[6].get<double>();
      body.spec.vmax_u_per_s = b[7].get<double>();
      body.spec.role = enum_from(b[8], sim::EnemyRole::chaser, "enemy role");
      body.goal = {b[9].get<double>(), b[10].get<double>()};
      body.credit = b[11].get<std::uint32_t>();
      body.credit_tick = b[12].get<std::int64_t>();
      body.expires_tick = b[13].get<std::int64_t>();
      if (!s.bodies.emplace(sim::BallId(b[0].get<std::uint32_t>()), body).second)
        return std::string("bodies: an id twice");
    }
  } catch (const std::exception& e) {
    return std::string("checkpoint: ") + field + ": " + e.what();
  }
  return s;
}

}  // namespace fts::host
