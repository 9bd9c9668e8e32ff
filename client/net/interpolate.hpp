// Smooth motion: the client draws a fixed delay behind the newest snapshot, between the
// two snapshots around that moment. Pure: times and ticks are passed in.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

#include "fts/protocol/snapshot.hpp"

namespace fts::client {

using protocol::Snapshot;

// Balls of b, moved to where they were at fraction alpha (0..1) of the way from a to b
// (balls new in b stay where b has them); phase, level, players and events come from b.
Snapshot interpolate(const Snapshot& a, const Snapshot& b, double alpha);

// Estimates the server's tick at a local time from snapshot arrivals. It reads the
// least delayed arrival of the last 3 s (the one that came soonest after its tick) as
// "on time": it moves up to a less delayed arrival at once, and down, when that one leaves
// the window, by at most 5 % of the time passing, so that it follows a server that runs
// slow (a loaded host skips ticks) without running backwards. It jumps when far off (a
// server restart). The jitter buffer measures lateness against this same clock (issue 37:
// a clock that followed a slow server at only 1 % ran ahead of the snapshots, which the
// buffer's delay, measured against its own estimate, did not cover: stalls at 150 ms).
class ServerClock {
 public:
  explicit ServerClock(double tick_rate_hz = 100) : tick_rate_hz_(tick_rate_hz) {}
  void set_tick_rate(double hz) { tick_rate_hz_ = hz > 0 ? hz : 100; }
  void observe(std::uint32_t tick, std::uint64_t now_ms);
  // Estimated server tick now (fractional); 0 before the first observation.
  double tick_at(std::uint64_t now_ms) const;
  bool valid() const { return valid_; }
  void reset() { valid_ = false; window_.clear(); }

 private:
  double tick_rate_hz_;
  bool valid_ = false;
  double offset_ = 0;  // server tick - local ms * rate / 1000
  std::uint64_t last_ms_ = 0;
  struct Sample {
    std::uint64_t at_ms;
    double offset;  // this arrival's: larger is less delayed
  };
  std::deque<Sample> window_;  // the last 3 s of arrivals
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
