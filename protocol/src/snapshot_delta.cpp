#include "fts/protocol/snapshot_delta.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "fts/protocol/codec.hpp"
#include "quanta.hpp"
#include "tables.hpp"

namespace fts::protocol {
namespace {

using wire::from_quanta;
using wire::to_quanta;
// A value the client rebuilt from deltas, in quanta.
std::int64_t rebuilt(double v) { return to_quanta(v, wire::kMaxRebuiltQuanta); }

BallEntry full_entry(const BallState& b) {
  return {b.id, true, to_quanta(b.x), to_quanta(b.y), to_quanta(b.vx), to_quanta(b.vy),
          to_quanta(b.radius), to_quanta(b.mass), b.kind, b.owner};
}

template <class T>
const T* find_by_id(const std::vector<T>& items, std::uint32_t id) {
  auto it = std::lower_bound(items.begin(), items.end(), id,
                             [](const T& item, std::uint32_t key) { return item.id < key; });
  return it != items.end() && it->id == id ? &*it : nullptr;
}

// Bytes one list item adds to an encoded part, at most (its encoding and a separator).
template <class K, class T>
std::size_t item_bytes(Encoding encoding, const K& kind, const T& item, std::string& scratch) {
  if (encoding == Encoding::msgpack) {
    wire::MsgpackCounter c;
    kind.put(c, item);
    return c.bytes;
  }
  scratch.clear();
  wire::JsonWriter w(scratch);
  kind.put(w, item);
  return scratch.size() + 1;  // the comma
}

// The delta of two quantized snapshots (the per-client part of the work), into `m`,
// whose lists keep their capacity from the last time (no allocation in the steady state).
void make_delta(const Snapshot& current, const Snapshot* base, std::uint32_t hz, SnapshotMsg& m,
                std::vector<BallEntry>& motions) {
  m.base.reset();
  m.part = 0;
  m.parts = 1;
  m.tick_rate_hz = 0;
  m.balls.clear();
  m.gone.clear();
  m.players.clear();
  m.left.clear();
  m.events.clear();
  motions.clear();
  m.tick = current.tick;
  m.phase = current.phase;
  m.level = current.level;
  m.deadline_tick = current.deadline_tick;
  if (base) {
    m.base = base->tick;
    // No prediction over more than 4 s: an entry stays within the wire's range.
    if (hz > kMaxTickRateHz || current.tick - base->tick > 4 * static_cast<std::uint64_t>(hz)) hz = 0;
    m.tick_rate_hz = hz;
  }
  const std::uint32_t ticks = base ? current.tick - base->tick : 0;
  // Full entries first, then motion entries (the order the wire keeps them in).
  for (const auto& b : current.balls) {
    const BallState* old = base ? find_by_id(base->balls, b.id) : nullptr;
    BallEntry e = full_entry(b);
    if (old) {
      const BallEntry o = full_entry(*old);
      if (o.radius == e.radius && o.mass == e.mass && o.kind == e.kind && o.owner == e.owner) {
        if (o == e) continue;  // unchanged: the client keeps the base's copy
        e.full = false;
        e.x -= o.x + predicted_step(o.vx, ticks, m.tick_rate_hz);
        e.y -= o.y + predicted_step(o.vy, ticks, m.tick_rate_hz);
        e.vx -= o.vx, e.vy -= o.vy;
        e.radius = e.mass = 0, e.kind = BallKind::enemy, e.owner = 0;
        motions.push_back(e);
        continue;
      }
    }
    m.balls.push_back(e);
  }
  m.balls.insert(m.balls.end(), motions.begin(), motions.end());
  for (const auto& p : current.players) {
    const PlayerState* old = base ? find_by_id(base->players, p.id) : nullptr;
    PlayerEntry e;
    e.id = p.id;
    // The player table names every field once: a field added there is diffed here.
    if (wire::diff(wire::kPlayerSynced, p, old, e) || !old) m.players.push_back(std::move(e));
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
}

}  // namespace

std::int64_t predicted_step(std::int64_t v_q, std::uint32_t ticks, std::uint32_t tick_rate_hz) {
  if (tick_rate_hz == 0 || ticks > kMaxPredictionTicks) return 0;
  v_q = std::clamp(v_q, -2 * kMaxQuantized, 2 * kMaxQuantized);  // |v * ticks| < 2^62
  const std::int64_t num = v_q * ticks, hz = tick_rate_hz;
  return num >= 0 ? (num + hz / 2) / hz : -((-num + hz / 2) / hz);
}

SnapshotMsg make_snapshot_msg(const Snapshot& current, const Snapshot* base, std::uint32_t tick_rate_hz) {
  std::optional<Snapshot> base_q;
  if (base) base_q = quantize(*base);
  SnapshotMsg m;
  std::vector<BallEntry> motions;
  make_delta(quantize(current), base_q ? &*base_q : nullptr, tick_rate_hz, m, motions);
  return m;
}

std::vector<SnapshotMsg> split_snapshot(SnapshotMsg message, Encoding encoding, std::size_t budget) {
  std::vector<SnapshotMsg> out;
  split_snapshot_into(message, encoding, budget, out);
  return out;
}

void split_snapshot_into(SnapshotMsg& whole, Encoding encoding, std::size_t budget,
                         std::vector<SnapshotMsg>& parts) {
  // The usual case, one part: swapped into the reused part (both keep their lists'
  // capacity for the next time).
  if (whole.balls.size() <= kMaxBallsPerMessage && whole.players.size() <= kMaxPlayersPerMessage &&
      whole.events.size() <= kMaxEventsPerMessage && snapshot_payload_bytes(encoding, whole) <= budget) {
    parts.resize(1);
    std::swap(parts[0], whole);
    return;
  }
  SnapshotMsg message = whole;
  if (message.events.size() > kMaxEventsPerMessage)
    message.events.erase(message.events.begin(), message.events.end() - kMaxEventsPerMessage);
  // Each entry is measured once; a part's size is bounded by its skeleton (measured with
  // the widest part numbers and list headers) plus the sizes of the entries put in it.
  std::string scratch;
  const auto& player_kind = wire::kPlayerMap;
  const wire::BallKindOfEntry ball_kind;
  std::vector<std::size_t> player_bytes, ball_bytes;
  for (const auto& p : message.players) player_bytes.push_back(item_bytes(encoding, player_kind, p, scratch));
  for (const auto& b : message.balls) ball_bytes.push_back(item_bytes(encoding, ball_kind, b, scratch));
  constexpr std::size_t kListHeaderSlack = 2 * 4;  // array16 headers of two lists
  for (;;) {
    // Greedy: fill each part with players, then balls, while it fits.
    std::vector<SnapshotMsg> out;
    std::vector<std::size_t> used;
    auto start_part = [&] {
      SnapshotMsg part;
      part.tick = message.tick;
      part.base = message.base;
      part.part = kMaxSnapshotParts - 1;
      part.parts = kMaxSnapshotParts;
      part.phase = message.phase;
      part.level = message.level;
      part.deadline_tick = message.deadline_tick;
      part.tick_rate_hz = message.tick_rate_hz;
      if (out.empty()) {
        part.gone = message.gone;
        part.left = message.left;
        part.events = message.events;
      }
      used.push_back(snapshot_payload_bytes(encoding, part) + kListHeaderSlack);
      out.push_back(std::move(part));
    };
    start_part();
    bool ok = used.back() <= budget;
    auto add = [&](auto member, const auto& item, std::size_t bytes, std::size_t max_items) {
      if ((out.back().*member).size() >= max_items || used.back() + bytes > budget) {
        if (out.size() >= kMaxSnapshotParts) return false;
        start_part();
        if (used.back() + bytes > budget) return false;
      }
      (out.back().*member).push_back(item);
      used.back() += bytes;
      return true;
    };
    for (std::size_t i = 0; ok && i < message.players.size(); ++i)
      ok = add(&SnapshotMsg::players, message.players[i], player_bytes[i], kMaxPlayersPerMessage);
    for (std::size_t i = 0; ok && i < message.balls.size(); ++i)
      ok = add(&SnapshotMsg::balls, message.balls[i], ball_bytes[i], kMaxBallsPerMessage);
    if (ok) {
      for (std::size_t k = 0; k < out.size(); ++k) {
        out[k].part = static_cast<std::uint32_t>(k);
        out[k].parts = static_cast<std::uint32_t>(out.size());
      }
      parts = std::move(out);
      return;
    }
    if (message.events.empty()) break;
    // Reduced: the oldest half of the events goes.
    message.events.erase(message.events.begin(), message.events.begin() + (message.events.size() + 1) / 2);
  }
  parts.clear();  // cannot fit: the caller sends nothing (never an oversize datagram)
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
        part.phase != first.phase || part.level != first.level || part.deadline_tick != first.deadline_tick ||
        part.tick_rate_hz != first.tick_rate_hz)
      return Reject::garbage;
    for (auto id : part.gone) balls.erase(id);
    for (auto id : part.left) players.erase(id);
  }
  for (const auto& part : parts) {
    for (const auto& e : part.balls) {
      if (e.full) {
        balls[e.id] = BallState{e.id, from_quanta(e.x), from_quanta(e.y), from_quanta(e.vx), from_quanta(e.vy),
                                from_quanta(e.radius), from_quanta(e.mass), e.kind, e.owner};
        continue;
      }
      auto it = balls.find(e.id);
      if (it == balls.end()) return Reject::unknown_base;
      BallState& b = it->second;
      const std::uint32_t ticks = first.base ? first.tick - *first.base : 0;  // decoded: always a delta
      b.x = from_quanta(rebuilt(b.x) + predicted_step(rebuilt(b.vx), ticks, first.tick_rate_hz) + e.x);
      b.y = from_quanta(rebuilt(b.y) + predicted_step(rebuilt(b.vy), ticks, first.tick_rate_hz) + e.y);
      b.vx = from_quanta(rebuilt(b.vx) + e.vx);
      b.vy = from_quanta(rebuilt(b.vy) + e.vy);
    }
    for (const auto& e : part.players) {
      auto [it, added] = players.try_emplace(e.id);
      if (added) it->second.id = e.id;
      wire::apply(wire::kPlayerSynced, e, it->second);
    }
    s.events.insert(s.events.end(), part.events.begin(), part.events.end());
  }
  s.balls.clear();
  for (auto& [id, b] : balls) s.balls.push_back(b);
  s.players.clear();
  for (auto& [id, p] : players) s.players.push_back(std::move(p));
  return s;
}

const std::vector<SnapshotMsg>& SnapshotSender::encode(const Snapshot& current, Encoding encoding,
                                                       std::size_t budget) {
  return encode(std::make_shared<const Snapshot>(quantize(current)), encoding, budget);
}

const std::vector<SnapshotMsg>& SnapshotSender::encode(SharedSnapshot current, Encoding encoding,
                                                       std::size_t budget) {
  make_delta(*current, base_for(*current), tick_rate_hz_, delta_, motions_);  // resets every field of delta_
  split_snapshot_into(delta_, encoding, budget, parts_);
  sent(std::move(current));
  return parts_;
}

const Snapshot* SnapshotSender::base_for(const Snapshot& current) const {
  // A base older than max_base_age_ticks is not used: the client gets a full snapshot.
  // Newest first: the acknowledged snapshot is nearly always one of the last.
  if (acked_ && *acked_ + max_base_age_ticks_ >= current.tick && *acked_ < current.tick) {
    for (std::size_t i = 0; i < count_; ++i)
      if (ticks_[slot_of(i)] == *acked_) return snapshots_[slot_of(i)].get();
  }
  return nullptr;
}

void SnapshotSender::remove(std::size_t newest) {
  for (std::size_t i = newest; i > 0; --i) {
    ticks_[slot_of(i)] = ticks_[slot_of(i - 1)];
    snapshots_[slot_of(i)] = std::move(snapshots_[slot_of(i - 1)]);
  }
  next_ = (next_ + kHistory - 1) % kHistory;
  snapshots_[next_].reset();
  --count_;
}

void SnapshotSender::sent(SharedSnapshot current) {
  const std::uint32_t tick = current->tick;
  for (std::size_t i = 0; i < count_;) {  // a tick sent again: its old entry goes (rare)
    if (ticks_[slot_of(i)] == tick) remove(i);  // the next older one is at i now
    else ++i;
  }
  ticks_[next_] = tick;
  snapshots_[next_] = std::move(current);  // the oldest's slot once full
  next_ = (next_ + 1) % kHistory;
  if (count_ < kHistory) ++count_;
}

void SnapshotSender::on_ack(std::uint32_t tick) {
  if (acked_ && tick <= *acked_) return;
  for (std::size_t i = 0; i < count_; ++i)  // newest first, as base_for
    if (ticks_[slot_of(i)] == tick) {
      acked_ = tick;
      return;
    }
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
