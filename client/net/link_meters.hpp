// The small pieces of the client's game loop that keep state between frames, each with
// one job: how many snapshots are lost, which events are new. (When to send input is
// the protocol's: ClientEndpoint::hold_input.)
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <tuple>
#include <vector>

#include "fts/protocol/messages.hpp"
#include "fts/protocol/snapshot.hpp"

namespace fts::client {

// Snapshots lost, from the gaps in their ticks, over the last few seconds.
class LossMeter {
 public:
  void on_snapshot(std::uint32_t tick, double ticks_per_snapshot);
  // 0..100, or < 0 before there is anything to judge.
  double percent() const;

 private:
  std::uint32_t last_tick_ = 0;
  double expected_ = 0, received_ = 0;
};

// Snapshots repeat the events of the last moments; this passes each one once, by its
// seq (PROTOCOL.md 8.4).
class EventFeed {
 public:
  // The events of `s` newer than every event passed before, in seq order.
  std::vector<protocol::Event> fresh(const protocol::Snapshot& s);
  // A (re)joined session sees the room's recent events again, some from before it came:
  // events of ticks before `tick` (the welcome's server tick) are not fresh.
  void start_at(std::uint32_t tick) { since_tick_ = tick; }

 private:
  std::uint32_t last_seq_ = 0;
  std::uint32_t since_tick_ = 0;
};

}  // namespace fts::client
