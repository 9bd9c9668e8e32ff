// fts-client --forget-me (issue 41, PROTOCOL.md 4.7c): asks the player to confirm (unless
// --yes), connects with the identity, sends `cmd forget`, waits for its result, leaves
// without a trace (bye "probe") and says what the server did. No raw terminal.
#pragma once

#include <string>

#include "client_options.hpp"
#include "fts/io/udp.hpp"

namespace fts::client {

// The exit status: 0 erased (or kept for erasure by the server), 1 not (said on stderr).
int forget_me(fts::io::asio::io_context& io, const Options& opts, const fts::io::udp::endpoint& server,
              const std::string& identity_path);

}  // namespace fts::client
