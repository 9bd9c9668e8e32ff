// Rooms that move (issue 42): the channel between two fts-servers of a fleet. A draining
// or moving server hands a room to a peer over TCP; the peer resumes it from its journal
// (GameHost::adopt_room) at the tick it left, and only then are the room's clients told
// where it went (`moved`, PROTOCOL.md 4.9b). Both ends prove the fleet's shared secret.
//
// The exchange (PROTOCOL.md 14), up to kMaxRoomsPerExchange rooms per TCP connection:
//   peer   -> sender  "FTSHOV01" and a 32-byte random challenge
//   sender -> peer    a frame: the request (JSON: each room, its tick, its journal's segments)
//   peer   -> sender  a frame: the reply (JSON: the peer's game port, each room taken or why not)
// A frame is a 4-byte big-endian length n (at most 64 MiB), n bytes of JSON and a 32-byte
// HMAC-SHA-256 (libsodium crypto_auth_hmacsha256) over a label ("fts-handover-1 request" or
// "fts-handover-1 reply"), the challenge and the JSON, keyed with BLAKE2b-256 of the secret
// file's bytes. The challenge makes a recorded frame useless on another connection.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/game_host.hpp"
#include "fts/io/asio.hpp"

namespace fts::server {

class HandoverChannel {
 public:
  // key: handover::read_secret_file's. game_port: this server's UDP port (a peer's clients are sent
  // to the host the peer was reached at, on the port its reply names). now_ms: the loop's
  // clock; flush: sends what the host queued (the `moved` messages).
  HandoverChannel(boost::asio::io_context& io, GameHost& host, std::string key, std::uint16_t game_port,
                  std::function<std::uint64_t()> now_ms, std::function<void()> flush);
  ~HandoverChannel();
  HandoverChannel(const HandoverChannel&) = delete;
  HandoverChannel& operator=(const HandoverChannel&) = delete;

  // Takes rooms from peers on ADDR:PORT (--handover-listen): "" or why not.
  std::string listen(const std::string& address);
  std::uint16_t port() const;

  // Hands room `code` to the peer at HOST:PORT (its --handover-listen). `done` gets the
  // console's reply when it ends either way: {"ok":true,"room","to","tick","clients_told","ms"}
  // or {"ok":false,"error"} (the room then plays on here).
  using Done = std::function<void(nlohmann::ordered_json)>;
  void hand_over(const std::string& code, const std::string& peer, Done done);
  // Several rooms to one peer, in exchanges of up to kMaxRoomsPerExchange rooms (their
  // journals sync together, the peer takes them in one go): `each` gets every room's
  // reply as hand_over's `done` would, in no set order.
  using EachDone = std::function<void(const std::string& code, nlohmann::ordered_json)>;
  void hand_over(const std::vector<std::string>& codes, const std::string& peer, EachDone each);
  static constexpr std::size_t kMaxRoomsPerExchange = 64;

  struct Impl;

 private:
  std::shared_ptr<Impl> impl_;
};

}  // namespace fts::server
