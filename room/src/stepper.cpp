#include "fts/room/stepper.hpp"

#include <utility>

#include "fts/room/snapshot_build.hpp"
#include "fts/sim/match_view.hpp"

namespace fts::room {

RoomStepper::RoomStepper(const sim::MatchConfig& cfg, std::uint64_t seed) : match_(sim::make_match(cfg, seed)) {}

RoomStepper::RoomStepper(sim::MatchState state, std::uint32_t event_seq)
    : match_(std::move(state)), event_seq_(event_seq) {}

sim::TickOutput RoomStepper::step(const sim::TickInputs& inputs, std::vector<protocol::Event>* fresh) {
  sim::TickOutput out = sim::step(match_, inputs);
  std::vector<protocol::Event> wire;
  append_wire_events(match_.tick, out.events, wire);
  for (auto& w : wire) {
    w.seq = ++event_seq_;
    recent_.push_back(w);
    if (fresh) fresh->push_back(w);
  }
  while (recent_.size() > kRecentEvents) recent_.pop_front();
  return out;
}

protocol::Snapshot RoomStepper::snapshot() const { return build_snapshot(sim::make_view(match_), recent_); }

}  // namespace fts::room
