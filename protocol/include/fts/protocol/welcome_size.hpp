// The size of the largest welcome a server with these settings sends (issue 36): the
// welcome is the reply to a hello and never larger (PROTOCOL.md 5.1), and it carries the
// match configuration's client fields, so a configuration with long enough numbers could
// make it too large to send. A server checks this when it starts.
#pragma once

#include <cstddef>

#include "fts/protocol/messages.hpp"

namespace fts::protocol {

// Sealed bytes of `settings` with its per-session fields at their longest (player id,
// server tick, token, a room code, reconnected, spectator), in the larger encoding.
std::size_t largest_welcome_bytes(Welcome settings);

}  // namespace fts::protocol
