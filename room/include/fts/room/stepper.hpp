// The room stepper: one match stepped tick by tick, its events numbered and the recent
// ones kept, exactly as a client is sent them. The server's rooms, the journal's resume,
// `fts-server --replay`, `fts-sim --inputs` and `fts-client --replay` all step a match
// through this one class, so a replay shows what a client was sent, bit for bit.
// Pure: no clock, no file, no socket.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "fts/protocol/snapshot.hpp"
#include "fts/sim/match.hpp"

namespace fts::room {

// The events a snapshot carries (PROTOCOL.md 8.4): the newest this many, oldest first.
inline constexpr std::size_t kRecentEvents = 48;

class RoomStepper {
 public:
  RoomStepper() = default;
  RoomStepper(const sim::MatchConfig& cfg, std::uint64_t seed);
  // Takes a match up where it was (a journal's resume): its state and the seq of the
  // newest event it had numbered; the recent window starts empty.
  RoomStepper(sim::MatchState state, std::uint32_t event_seq);

  // Steps one tick. The tick's wire events (numbered) are appended to `fresh` if given.
  sim::TickOutput step(const sim::TickInputs& inputs, std::vector<protocol::Event>* fresh = nullptr);

  // What a client is sent now: the public state with the recent events.
  protocol::Snapshot snapshot() const;

  const sim::MatchState& match() const { return match_; }
  sim::MatchState& match() { return match_; }
  std::uint32_t event_seq() const { return event_seq_; }
  const std::deque<protocol::Event>& recent() const { return recent_; }

 private:
  sim::MatchState match_;
  std::deque<protocol::Event> recent_;
  std::uint32_t event_seq_ = 0;  // seq of the newest event numbered
};

}  // namespace fts::room
