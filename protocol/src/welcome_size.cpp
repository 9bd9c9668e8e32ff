#include "fts/protocol/welcome_size.hpp"

#include <algorithm>

#include "fts/protocol/codec.hpp"
#include "fts/protocol/header.hpp"

namespace fts::protocol {

std::size_t largest_welcome_bytes(Welcome w) {
  w.player_id = 0xFFFFFFFFu;
  w.server_tick = 0xFFFFFFFFu;
  w.token = std::string(32, 'f');
  w.room = "WWWWW";  // the server's room codes are 5 letters (PROTOCOL.md 5.6)
  w.reconnected = true;
  w.spectator = true;
  std::size_t most = 0;
  for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
    Header h;
    h.encoding = enc;
    h.session = 0xFFFFFFFFu;
    h.sequence = 0xFFFF;
    h.ack = 0xFFFF;
    most = std::max(most, encode_datagram(h, {w}).size() + kSealTagBytes);
  }
  return most;
}

}  // namespace fts::protocol
