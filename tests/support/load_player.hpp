// What each client of the in-memory load rigs does at a tick (test_rooms_load.cpp,
// tests/bench/host_bench.cpp): ready every 500 ms in the lobby and the shop, else hold
// an input that changes every 300-400 ms, on the lean uplink as fts-bot does.
#pragma once

#include <cstddef>
#include <cstdint>

#include "fts/protocol/client.hpp"

namespace fts::test {

inline void play_load_tick(protocol::ClientEndpoint& c, std::size_t i, std::uint64_t now) {
  if (c.state() != protocol::ClientState::connected) return;
  const auto phase = c.latest_snapshot() ? c.latest_snapshot()->phase : protocol::Phase::lobby;
  if (phase == protocol::Phase::lobby || phase == protocol::Phase::shop) {
    if (now % 500 == 0) c.send_command(protocol::CommandOp::ready, 0, now);
    return;
  }
  c.hold_input({0, static_cast<std::int8_t>((now / 400 + i) % 3 - 1), static_cast<std::int8_t>((now / 300 + i) % 3 - 1),
                false},
               now);
}

}  // namespace fts::test
