// fts-server's event loop: one io_context, one UDP socket, the tick timer, the stats
// timer and the signals. The only translation unit of fts-server that includes Asio.
#pragma once

#include <ostream>

#include "app/game_host.hpp"
#include "app/options.hpp"

namespace fts::server {

// Binds, logs the ready line, runs until SIGINT/SIGTERM/SIGHUP, tells the clients, returns 0.
// Returns 1 (after logging why) when the address cannot be bound.
// The rooms' records are flushed by the host's shutdown (their journals' writers).
int run_udp_server(const Options& options, GameHost& host);

}  // namespace fts::server
