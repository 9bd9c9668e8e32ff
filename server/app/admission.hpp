// Who gets in. The endpoint's per-host limits are decided here, in one place, from
// --max-per-address (the seats a host may hold, and the datagram and handshake rates
// that follow from them); the endpoint enforces them (address_full, rate_limited).
// GameHost::admit, in admission.cpp, picks the room of a new player whose hello passed
// every other check: quick play, create, join or spectate, and their refusals.
#pragma once

#include <cstdint>

#include "fts/protocol/server.hpp"

namespace fts::server {

void apply_address_limits(protocol::ServerConfig& config, std::uint32_t max_per_address);

}  // namespace fts::server
