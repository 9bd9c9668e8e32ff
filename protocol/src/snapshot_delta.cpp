#include "fts/protocol/snapshot_delta.hpp"

#include <algorithm>
#include <cmath>

#include "fts/protocol/codec.hpp"

namespace fts::protocol {
namespace {

std::int64_t qv(double v) { return static_cast<std::int64_t>(std::llround(v * kQuantaPerUnit)); }
double unq(std::int64_t v) { return static_cast<double>(v) / kQuantaPerUnit; }

BallEntry full_entry(const BallState& b) {
  return {b.id, true, qv(b.x), qv(b.y), qv(b.vx), qv(b.vy), qv(b.radius), qv(b.mass), b.kind, b.owner};
}

PlayerEntry player_entry(const PlayerState& p, const PlayerState* base) {
  PlayerEntry e;
  e.id = p.id;
  auto set = [base](auto& out, const auto& now, auto member) {
    if (!base || !(base->*member == now)) out = now;
  };
  set(e.name, p.name, &PlayerState::name);
  set(e.coins, p.coins, &PlayerState::coins);
  set(e.lives, p.lives, &PlayerState::lives);
  set(e.mass, p.mass, &PlayerState::mass);
  set(e.vmax_u_per_s, p.vmax_u_per_s, &PlayerState::vmax_u_per_s);
  set(e.accel_u_per_s2, p.accel_u_per_s2, &PlayerState::accel_u_per_s2);
  set(e.multiplier, p.multiplier, &PlayerState::multiplier);
  set(e.bank, p.bank, &PlayerState::bank);
  set(e.weapon, p.weapon, &PlayerState::weapon);
  set(e.prices, p.prices, &PlayerState::prices);
  set(e.ready, p.ready, &PlayerState::ready);
  set(e.alive, p.alive, &PlayerState::alive);
  return e;
}

bool has_changes(const PlayerEntry& e) {
  return e.name || e.coins || e.lives || e.mass || e.vmax_u_per_s || e.accel_u_per_s2 ||
         e.multiplier || e.bank || e.weapon || e.prices || e.ready || e.alive;
}

void apply_player(PlayerState& p, const PlayerEntry& e) {
  if (e.name) p.name = *e.name;
  if (e.coins) p.coins = *e.coins;
  if (e.lives) p.lives = *e.lives;
  if (e.mass) p.mass = *e.mass;
  if (e.vmax_u_per_s) p.vmax_u_per_s = *e.vmax_u_per_s;
  if (e.accel_u_per_s2) p.accel_u_per_s2 = *e.accel_u_per_s2;
  if (e.multiplier) p.multiplier = *e.multiplier;
  if (e.bank) p.bank = *e.bank;
  if (e.weapon) p.weapon = *e.weapon;
  if (e.prices) p.prices = *e.prices;
  if (e.ready) p.ready = *e.ready;
  if (e.alive) p.alive = *e.alive;
}

template <class T>
const T* find_by_id(const std::vector<T>& items, std::uint32_t id) {
  auto it = std::lower_bound(items.begin(), items.end(), id,
                             [](const T& item, std::uint32_t key) { return item.id < key; });
  return it != items.end() && it->id == id ? &*it : nullptr;
}

std::size_t payload_size(const SnapshotMsg& m, Encoding encoding) {
  return encode_payload(encoding, {m}).size();
}

}  // namespace

SnapshotMsg make_snapshot_msg(const Snapshot& current_in, const Snapshot* base_in) {
  const Snapshot current = quantize(current_in);
  std::optional<Snapshot> base_q;
  if (base_in) base_q = quantize(*base_in);
  const Snapshot* base = base_q ? &*base_q : nullptr;

  SnapshotMsg m;
  m.tick = current.tick;
  m.phase = current.phase;
  m.level = current.level;
  m.deadline_tick = current.deadline_tick;
  if (base) m.base = base->tick;
  for (const auto& b : current.balls) {
    const BallState* old = base ? find_by_id(base->balls, b.id) : nullptr;
    BallEntry e = full_entry(b);
    if (old) {
      const BallEntry o = full_entry(*old);
      if (o.radius == e.radius && o.mass == e.mass && o.kind == e.kind && o.owner == e.owner) {
        if (o == e) continue;  // unchanged: the client keeps the base's copy
        e.full = false;
        e.x -= o.x, e.y -= o.y, e.vx -= o.vx, e.vy -= o.vy;
        e.radius = e.mass = 0, e.kind = BallKind::enemy, e.owner = 0;
      }
    }
    m.balls.push_back(e);
  }
  for (const auto& p : current.players) {
    const PlayerState* old = base ? find_by_id(base->players, p.id) : nullptr;
    PlayerEntry e = player_entry(p, old);
    if (!old || has_changes(e)) m.players.push_back(std::move(e));
  }
  if (base) {
    for (const auto& b : base->balls)
      if (!find_by_id(current.balls, b.id)) m.gone.push_back(b.id);
    for (const auto& p : base->players)
      if (!find_by_id(current.players, p.id)) m.left.push_back(p.id);
  }
  // A delta carries the events its base did not have; a full snapshot the recent window.
  const std::uint32_t base_seq = base && !base->events.empty() ? base->events.back().seq : 0;
  for (const auto& e : current.events)
    if (!base || e.seq > base_seq) m.events.push_back(e);
  return m;
}

std::vector<SnapshotMsg> split_snapshot(SnapshotMsg message, Encoding encoding, std::size_t budget) {
  if (message.balls.size() <= kMaxBallsPerMessage && message.players.size() <= kMaxPlayersPerMessage &&
      message.events.size() <= kMaxEventsPerMessage && payload_size(message, encoding) <= budget)
    return {message};
  if (message.events.size() > kMaxEventsPerMessage)
    message.events.erase(message.events.begin(), message.events.end() - kMaxEventsPerMessage);
  for (;;) {
    // Greedy: fill each part with players, then balls, while it fits. Sizes are measured
    // with the widest part/parts numbers, so setting the real ones never grows a part.
    std::vector<SnapshotMsg> out;
    auto start_part = [&] {
      SnapshotMsg part;
      part.tick = message.tick;
      part.base = message.base;
      part.part = kMaxSnapshotParts - 1;
      part.parts = kMaxSnapshotParts;
      part.phase = message.phase;
      part.level = message.level;
      part.deadline_tick = message.deadline_tick;
      if (out.empty()) {
        part.gone = message.gone;
        part.left = message.left;
        part.events = message.events;
      }
      out.push_back(std::move(part));
    };
    start_part();
    bool ok = payload_size(out.back(), encoding) <= budget;
    auto add = [&](auto member, const auto& item, std::size_t max_items) {
      auto& list = out.back().*member;
      list.push_back(item);
      const bool full = list.size() > max_items || payload_size(out.back(), encoding) > budget;
      if (!full) return true;
      list.pop_back();
      if (out.size() >= kMaxSnapshotParts) return false;
      start_part();
      (out.back().*member).push_back(item);
      return payload_size(out.back(), encoding) <= budget;
    };
    for (std::size_t i = 0; ok && i < message.players.size(); ++i)
      ok = add(&SnapshotMsg::players, message.players[i], kMaxPlayersPerMessage);
    for (std::size_t i = 0; ok && i < message.balls.size(); ++i)
      ok = add(&SnapshotMsg::balls, message.balls[i], kMaxBallsPerMessage);
    if (ok) {
      for (std::size_t k = 0; k < out.size(); ++k) {
        out[k].part = static_cast<std::uint32_t>(k);
        out[k].parts = static_cast<std::uint32_t>(out.size());
      }
      return out;
    }
    if (message.events.empty()) break;
    // Reduced: the oldest half of the events goes.
    message.events.erase(message.events.begin(), message.events.begin() + (message.events.size() + 1) / 2);
  }
  return {};  // cannot fit: the caller sends nothing (never an oversize datagram)
}

Decoded<Snapshot> apply_snapshot(const std::vector<SnapshotMsg>& parts, const Snapshot* base) {
  if (parts.empty()) return Reject::truncated;
  const SnapshotMsg& first = parts.front();
  if (first.base.has_value() != (base != nullptr)) return Reject::unknown_base;
  if (base && base->tick != *first.base) return Reject::unknown_base;
  Snapshot s;
  if (base) s = *base;
  s.tick = first.tick;
  s.phase = first.phase;
  s.level = first.level;
  s.deadline_tick = first.deadline_tick;
  s.events.clear();
  std::map<std::uint32_t, BallState> balls;
  for (const auto& b : s.balls) balls[b.id] = b;
  std::map<std::uint32_t, PlayerState> players;
  for (const auto& p : s.players) players[p.id] = p;
  for (const auto& part : parts) {
    if (part.tick != first.tick || part.base != first.base || part.parts != first.parts ||
        part.phase != first.phase || part.level != first.level || part.deadline_tick != first.deadline_tick)
      return Reject::garbage;
    for (auto id : part.gone) balls.erase(id);
    for (auto id : part.left) players.erase(id);
  }
  for (const auto& part : parts) {
    for (const auto& e : part.balls) {
      if (e.full) {
        balls[e.id] = BallState{e.id, unq(e.x), unq(e.y), unq(e.vx), unq(e.vy),
                                unq(e.radius), unq(e.mass), e.kind, e.owner};
        continue;
      }
      auto it = balls.find(e.id);
      if (it == balls.end()) return Reject::unknown_base;
      BallState& b = it->second;
      b.x = unq(qv(b.x) + e.x);
      b.y = unq(qv(b.y) + e.y);
      b.vx = unq(qv(b.vx) + e.vx);
      b.vy = unq(qv(b.vy) + e.vy);
    }
    for (const auto& e : part.players) {
      auto [it, added] = players.try_emplace(e.id);
      if (added) it->second.id = e.id;
      apply_player(it->second, e);
    }
    s.events.insert(s.events.end(), part.events.begin(), part.events.end());
  }
  s.balls.clear();
  for (auto& [id, b] : balls) s.balls.push_back(b);
  s.players.clear();
  for (auto& [id, p] : players) s.players.push_back(std::move(p));
  return s;
}

std::vector<SnapshotMsg> SnapshotSender::encode(const Snapshot& current_in, Encoding encoding,
                                                std::size_t budget) {
  Snapshot current = quantize(current_in);
  const Snapshot* base = nullptr;
  // A base older than max_base_age_ticks is not used: the client gets a full snapshot.
  if (acked_ && *acked_ + max_base_age_ticks_ >= current.tick) {
    for (const auto& h : history_)
      if (h.tick == *acked_ && h.tick < current.tick) base = &h;
  }
  auto parts = split_snapshot(make_snapshot_msg(current, base), encoding, budget);
  std::erase_if(history_, [&](const Snapshot& h) { return h.tick == current.tick; });
  history_.push_back(std::move(current));
  if (history_.size() > kHistory) history_.pop_front();
  return parts;
}

void SnapshotSender::on_ack(std::uint32_t tick) {
  if (acked_ && tick <= *acked_) return;
  for (const auto& h : history_)
    if (h.tick == tick) acked_ = tick;
}

Decoded<std::optional<Snapshot>> SnapshotReceiver::accept(const SnapshotMsg& part) {
  if (latest_ && part.tick <= latest_->tick) return Reject::stale;
  const Snapshot* base = nullptr;
  if (part.base) {
    auto it = history_.find(*part.base);
    if (it == history_.end()) return Reject::unknown_base;
    base = &it->second;
  }
  auto& slots = pending_[part.tick];
  if (slots.empty()) slots.resize(part.parts);
  if (slots.size() != part.parts) return Reject::garbage;
  for (const auto& other : slots)
    if (other && (other->base != part.base || other->phase != part.phase || other->level != part.level))
      return Reject::garbage;
  if (slots[part.part]) return Reject::stale;  // duplicate part
  slots[part.part] = part;
  while (pending_.size() > kMaxPending) pending_.erase(pending_.begin());
  auto it = pending_.find(part.tick);
  if (it == pending_.end()) return std::optional<Snapshot>{};
  for (const auto& slot : it->second)
    if (!slot) return std::optional<Snapshot>{};
  std::vector<SnapshotMsg> all;
  for (auto& slot : it->second) all.push_back(std::move(*slot));
  pending_.erase(pending_.begin(), std::next(it));
  auto snapshot = apply_snapshot(all, base);
  if (!snapshot) return snapshot.error();
  history_[snapshot->tick] = *snapshot;
  while (history_.size() > kHistory) history_.erase(history_.begin());
  latest_ = *snapshot;
  std::vector<Event> events = snapshot->events;
  std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.seq < b.seq; });
  for (const auto& e : events)
    if (e.seq > delivered_event_seq_) {
      delivered_event_seq_ = e.seq;
      new_events_.push_back(e);
    }
  return std::optional<Snapshot>{std::move(*snapshot)};
}

std::vector<Event> SnapshotReceiver::take_events() { return std::exchange(new_events_, {}); }

}  // namespace fts::protocol
