// What the server's welcome tells the client's screen: whose ball is ours, the arena,
// the shop's terms, the tick rate, the room; and the welcome's numbers with the
// defaults used before one arrived.
#pragma once

#include <cstdint>
#include <optional>

#include "fts/protocol/messages.hpp"
#include "ui/view.hpp"

namespace fts::client {

void show_welcome(ViewState& view, const protocol::Welcome& w);
// How long the server keeps a player who left (s): 60 without a welcome.
std::uint64_t reconnect_window_s(const std::optional<protocol::Welcome>& w);
// The server's tick rate (Hz): 100 without a welcome.
double tick_rate_hz(const std::optional<protocol::Welcome>& w);

}  // namespace fts::client
