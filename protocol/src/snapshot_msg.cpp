// nlohmann mapping of SnapshotMsg (full snapshots and deltas), and quantize().
#include <algorithm>
#include <cmath>

#include "mapping.hpp"

namespace fts::protocol {

using nlohmann::json;
using namespace detail;

int shop_index(char item) {
  const auto it = sim::item_by_key(item);
  return it ? static_cast<int>(sim::index_of(*it)) : -1;
}

namespace {

constexpr const char* kPhaseNames[] = {"lobby", "play", "shop", "over"};

std::int64_t q(double v) {
  if (!std::isfinite(v)) return 0;
  const double scaled = std::round(v * kQuantaPerUnit);
  const double lim = static_cast<double>(kMaxQuantized);
  return static_cast<std::int64_t>(std::clamp(scaled, -lim, lim));
}
double unq(std::int64_t v) { return static_cast<double>(v) / kQuantaPerUnit; }
double clean(double v) { return std::isfinite(v) ? v : 0.0; }

json ball_to_json(const BallEntry& b) {
  if (!b.full) return json::array({b.id, b.x, b.y, b.vx, b.vy});
  return json::array({b.id, b.x, b.y, b.vx, b.vy, b.radius, b.mass,
                      static_cast<int>(b.kind), b.owner});
}

BallEntry ball_from_json(const json& j) {
  if (!j.is_array() || (j.size() != 5 && j.size() != 9)) fail(Reject::garbage);
  BallEntry b;
  b.full = j.size() == 9;
  const std::int64_t lim = b.full ? kMaxQuantized : 2 * kMaxQuantized;
  b.id = as_u32(j[0]);
  b.x = as_int(j[1], -lim, lim);
  b.y = as_int(j[2], -lim, lim);
  b.vx = as_int(j[3], -lim, lim);
  b.vy = as_int(j[4], -lim, lim);
  if (b.full) {
    b.radius = as_int(j[5], 0, kMaxQuantized);
    b.mass = as_int(j[6], 0, kMaxQuantized);
    b.kind = static_cast<BallKind>(as_int(j[7], 0, 2));
    b.owner = as_u32(j[8]);
  }
  return b;
}

json player_to_json(const PlayerEntry& p) {
  json j = json::object();
  j["i"] = p.id;
  if (p.name) j["n"] = *p.name;
  if (p.coins) j["c"] = *p.coins;
  if (p.lives) j["l"] = *p.lives;
  if (p.mass) j["m"] = clean(*p.mass);
  if (p.vmax_u_per_s) j["v"] = clean(*p.vmax_u_per_s);
  if (p.accel_u_per_s2) j["a"] = clean(*p.accel_u_per_s2);
  if (p.multiplier) j["x"] = clean(*p.multiplier);
  if (p.bank) j["b"] = *p.bank;
  if (p.weapon) j["w"] = static_cast<int>(*p.weapon);
  if (p.prices) j["p"] = *p.prices;
  if (p.ready) j["r"] = *p.ready;
  if (p.alive) j["al"] = *p.alive;
  return j;
}

PlayerEntry player_from_json(const json& j) {
  if (!j.is_object()) fail(Reject::garbage);
  PlayerEntry p;
  p.id = as_u32(field(j, "i"));
  if (const json* v = optional_field(j, "n")) {
    p.name = as_text(*v, kMaxNameBytes);
    if (p.name->empty()) fail(Reject::out_of_range);
  }
  if (const json* v = optional_field(j, "c")) p.coins = as_int(*v, 0, kMaxCoins);
  if (const json* v = optional_field(j, "l")) p.lives = static_cast<std::int32_t>(as_int(*v, 0, 1'000'000));
  if (const json* v = optional_field(j, "m")) p.mass = as_double(*v, 0, 1e15);
  if (const json* v = optional_field(j, "v")) p.vmax_u_per_s = as_double(*v, 0, 1e15);
  if (const json* v = optional_field(j, "a")) p.accel_u_per_s2 = as_double(*v, 0, 1e15);
  if (const json* v = optional_field(j, "x")) p.multiplier = as_double(*v, 0, 1e15);
  if (const json* v = optional_field(j, "b")) p.bank = as_bool(*v);
  if (const json* v = optional_field(j, "w")) p.weapon = static_cast<Weapon>(as_int(*v, 0, 1));
  if (const json* v = optional_field(j, "p")) {
    std::array<std::int64_t, sim::kItemCount> prices{};
    if (!v->is_array() || v->size() != prices.size()) fail(Reject::garbage);
    for (std::size_t i = 0; i < prices.size(); ++i) prices[i] = as_int((*v)[i], 0, kMaxCoins);
    p.prices = prices;
  }
  if (const json* v = optional_field(j, "r")) p.ready = as_bool(*v);
  if (const json* v = optional_field(j, "al")) p.alive = as_bool(*v);
  return p;
}

std::vector<std::uint32_t> ids_from_json(const json& j, std::size_t max_items) {
  std::vector<std::uint32_t> ids;
  for (const auto& v : as_array(j, max_items)) ids.push_back(as_u32(v));
  return ids;
}

}  // namespace

void to_json(json& j, const SnapshotMsg& m) {
  json balls = json::array();
  for (const auto& b : m.balls) balls.push_back(ball_to_json(b));
  json players = json::array();
  for (const auto& p : m.players) players.push_back(player_to_json(p));
  json events = json::array();
  for (const auto& e : m.events)
    events.push_back(json::array({e.seq, e.tick, static_cast<int>(e.kind), e.a, e.b, e.value}));
  j = json{{"tick", m.tick},
           {"part", m.part},
           {"parts", m.parts},
           {"phase", kPhaseNames[static_cast<int>(m.phase) & 3]},
           {"level", m.level},
           {"balls", std::move(balls)},
           {"players", std::move(players)}};
  if (m.base) j["base"] = *m.base;
  if (m.deadline_tick) j["dl"] = m.deadline_tick;
  if (!m.gone.empty()) j["gone"] = m.gone;
  if (!m.left.empty()) j["left"] = m.left;
  if (!m.events.empty()) j["events"] = std::move(events);
}

void from_json(const json& j, SnapshotMsg& m) {
  m = SnapshotMsg{};
  m.tick = as_u32(field(j, "tick"));
  if (const json* v = optional_field(j, "base")) {
    m.base = as_u32(*v);
    if (*m.base >= m.tick) fail(Reject::out_of_range);
  }
  m.parts = as_u32(field(j, "parts"), kMaxSnapshotParts);
  m.part = as_u32(field(j, "part"), kMaxSnapshotParts);
  if (m.parts == 0 || m.part >= m.parts) fail(Reject::out_of_range);
  const std::string phase = as_text(field(j, "phase"), 8);
  bool known = false;
  for (int i = 0; i < 4; ++i)
    if (phase == kPhaseNames[i]) m.phase = static_cast<Phase>(i), known = true;
  if (!known) fail(Reject::out_of_range);
  m.level = as_u32(field(j, "level"), 1'000'000);
  if (const json* v = optional_field(j, "dl")) m.deadline_tick = as_u32(*v);
  for (const auto& b : as_array(field(j, "balls"), kMaxBallsPerMessage)) {
    m.balls.push_back(ball_from_json(b));
    if (!m.base && !m.balls.back().full) fail(Reject::out_of_range);  // full needs full entries
  }
  for (const auto& p : as_array(field(j, "players"), kMaxPlayersPerMessage))
    m.players.push_back(player_from_json(p));
  if (const json* v = optional_field(j, "gone")) m.gone = ids_from_json(*v, kMaxBallsPerMessage);
  if (const json* v = optional_field(j, "left")) m.left = ids_from_json(*v, kMaxPlayersPerMessage);
  if (const json* v = optional_field(j, "events")) {
    for (const auto& e : as_array(*v, kMaxEventsPerMessage)) {
      if (!e.is_array() || e.size() != 6) fail(Reject::garbage);
      Event ev;
      ev.seq = as_u32(e[0]);
      if (ev.seq == 0) fail(Reject::out_of_range);
      ev.tick = as_u32(e[1]);
      ev.kind = static_cast<EventKind>(as_int(e[2], 0, static_cast<int>(EventKind::count_) - 1));
      ev.a = as_u32(e[3]);
      ev.b = as_u32(e[4]);
      ev.value = as_int(e[5], -kMaxCoins, kMaxCoins);
      m.events.push_back(ev);
    }
  }
}

Snapshot quantize(Snapshot s) {
  for (auto& b : s.balls) {
    b.x = unq(q(b.x));
    b.y = unq(q(b.y));
    b.vx = unq(q(b.vx));
    b.vy = unq(q(b.vy));
    b.radius = unq(std::max<std::int64_t>(0, q(b.radius)));
    b.mass = unq(std::max<std::int64_t>(0, q(b.mass)));
  }
  for (auto& p : s.players) {
    p.mass = std::clamp(clean(p.mass), 0.0, 1e15);
    p.vmax_u_per_s = std::clamp(clean(p.vmax_u_per_s), 0.0, 1e15);
    p.accel_u_per_s2 = std::clamp(clean(p.accel_u_per_s2), 0.0, 1e15);
    p.multiplier = std::clamp(clean(p.multiplier), 0.0, 1e15);
    p.coins = std::clamp<std::int64_t>(p.coins, 0, kMaxCoins);
    for (auto& price : p.prices) price = std::clamp<std::int64_t>(price, 0, kMaxCoins);
    p.lives = std::clamp(p.lives, 0, 1'000'000);
    if (p.name.size() > kMaxNameBytes) p.name.resize(kMaxNameBytes);
    for (char& c : p.name)
      if (c < 0x20 || c > 0x7E) c = '?';
    if (p.name.empty()) p.name.push_back('?');
  }
  std::sort(s.balls.begin(), s.balls.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  std::sort(s.players.begin(), s.players.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return s;
}

}  // namespace fts::protocol
