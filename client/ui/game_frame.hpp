// One frame of the live game, composed from what the client knows at `now_ms`: the
// remote balls a jitter buffer's delay behind the server clock (interpolated), the own
// ball predicted at the tick its inputs act (when predicting), outside play the newest
// snapshot as it is. Tells net what the screen shows (stalls, the own ball's motion).
#pragma once

#include <cstdint>
#include <optional>

#include "net/interpolate.hpp"
#include "net/net_timing.hpp"
#include "ui/screen.hpp"
#include "ui/view.hpp"

namespace fts::client {

// fixed_delay_ms: --interp-delay-ms (none: the jitter buffer's own delay). Sets
// view.delay_ms to the delay used.
Screen game_frame(const SnapshotBuffer& buffer, NetTiming& net, ViewState& view, TerminalSize size,
                  std::uint64_t now_ms, std::optional<int> fixed_delay_ms);

}  // namespace fts::client
