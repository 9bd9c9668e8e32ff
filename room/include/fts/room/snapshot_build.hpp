// The match's public state and events as the wire carries them.
#pragma once

#include <deque>
#include <vector>

#include "fts/protocol/snapshot.hpp"
#include "fts/sim/match_view.hpp"

namespace fts::room {

// Match events -> wire events (tick-stamped). Join refusals are not public.
void append_wire_events(std::int64_t tick, const std::vector<sim::Event>& events,
                        std::vector<protocol::Event>& out);

// The snapshot of `view` with the recent events (oldest first).
protocol::Snapshot build_snapshot(const sim::MatchView& view, const std::deque<protocol::Event>& recent);

}  // namespace fts::room
