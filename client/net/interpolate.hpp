// Smooth motion: the client draws a fixed delay behind the newest snapshot, between the
// two snapshots around that moment. Pure: times and ticks are passed in.
#pragma once

#include <cmath>
#include <cstdint>
#include <deque>
#include <optional>

#include "fts/protocol/snapshot.hpp"

namespace fts::client {

using protocol::Snapshot;

// Balls of b, moved to where they were at fraction alpha (0..1) of the way from a to b
// (balls new in b stay where b has them); phase, level, players and events come from b.
Snapshot interpolate(const Snapshot& a, const Snapshot& b, double alpha);

// The server's tick at a local time, as an offset (server tick - local ms * rate / 1000).
// Its owner (the jitter buffer) keeps the arrivals and hands it the offset of the least
// delayed one of the last 3 s (the one that came soonest after its tick), read as "on
// time": the clock moves up to it at once, and down, when that arrival has left the
// window, by at most 5 % of the time passing, so that it follows a server that runs slow
// (a loaded host skips ticks) without running backwards. The buffer measures lateness
// against this same clock (issue 37: a clock that followed a slow server at only 1 % ran
// ahead of the snapshots, which the buffer's delay, measured against its own estimate,
// did not cover: stalls at 150 ms).
class ServerClock {
 public:
  explicit ServerClock(double tick_rate_hz = 100) : tick_rate_hz_(tick_rate_hz > 0 ? tick_rate_hz : 100) {}
  // This arrival's offset: larger is less delayed.
  double offset_of(std::uint32_t tick, std::uint64_t at_ms) const {
    return static_cast<double>(tick) - static_cast<double>(at_ms) * tick_rate_hz_ / 1000.0;
  }
  // Start at this offset (the first arrival, or the server started again).
  void start(double offset, std::uint64_t now_ms);
  // Follow the least delayed recent arrival's offset.
  void follow(double best_offset, std::uint64_t now_ms);
  // Estimated server tick now (fractional); 0 before the first arrival.
  double tick_at(std::uint64_t now_ms) const;
  bool valid() const { return valid_; }
  // How far an offset is from the clock's, in seconds.
  double seconds_off(double offset) const { return std::abs(offset - offset_) / tick_rate_hz_; }

 private:
  double tick_rate_hz_;
  bool valid_ = false;
  double offset_ = 0;
  std::uint64_t last_ms_ = 0;
};

// The two snapshots to draw and how far between them.
struct Frame {
  const Snapshot* a = nullptr;
  const Snapshot* b = nullptr;
  double alpha = 0;
};

// Recent snapshots in tick order (newest last), at most `capacity`.
class SnapshotBuffer {
 public:
  explicit SnapshotBuffer(std::size_t capacity = 64) : capacity_(capacity) {}
  void push(Snapshot snapshot);  // out-of-order or duplicate ticks are dropped
  void clear() { snapshots_.clear(); }
  bool empty() const { return snapshots_.empty(); }
  const Snapshot* newest() const { return snapshots_.empty() ? nullptr : &snapshots_.back(); }
  // The pair around render_tick; before the oldest or after the newest, that one alone.
  Frame sample(double render_tick) const;
  std::size_t size() const { return snapshots_.size(); }

 private:
  std::size_t capacity_;
  std::deque<Snapshot> snapshots_;
};

}  // namespace fts::client
