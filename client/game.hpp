// The game loop of fts-client (game.cpp): keys in, inputs and commands out through the
// connection, snapshots in, a frame drawn, until the player quits or the server ends it.
// The terminal must be raw already (term::enter); main_client.cpp owns the program.
#pragma once

#include <string>

#include "client_options.hpp"
#include "fts/io/udp.hpp"

namespace fts::client {

struct GameEnd {
  int code = 0;            // the process's exit status
  std::string message;     // for stderr ("" when there is nothing to say)
  std::string stats_json;  // --stats-file's figures ("" without the flag)
};

GameEnd play(fts::io::asio::io_context& io, const Options& opts, const fts::io::udp::endpoint& server);

}  // namespace fts::client
