// A client's connection across reconnects: the one place reconnect-with-token lives.
// It holds the endpoint of the current attempt and the session token of the latest
// welcome; a new attempt presents the token, which takes our player back (within the
// server's reconnect window). Sans-I/O like the endpoint: each new attempt bumps
// attempt(), and the caller then sends from a fresh local port, because the server's
// answer to the old address belongs to the old session.
#pragma once

#include <cstdint>
#include <string>

#include "fts/protocol/client.hpp"

namespace fts::protocol {

class ClientConnection {
 public:
  // config.token, if set, takes a previous player back on the first attempt.
  // resume_when_lost: a connection lost after a welcome (timed out, or dropped by the
  // server) starts a new attempt by itself until the welcome's reconnect window passes.
  explicit ClientConnection(ClientConfig config, bool resume_when_lost = false);

  // Starts a new attempt (the first, or a reconnect) with the latest token.
  void connect(std::uint64_t now_ms);
  // The endpoint's timers, then the token of a new welcome and the resume rule.
  void update(std::uint64_t now_ms);
  // Our own clean disconnect (bye with `reason`): never resumed by itself.
  void leave(std::uint64_t now_ms, const std::string& reason = "quit");

  ClientEndpoint& endpoint() { return endpoint_; }
  const ClientEndpoint& endpoint() const { return endpoint_; }
  ClientState state() const { return endpoint_.state(); }
  // The latest welcome's token ("" until one came, unless the config gave one).
  const std::string& token() const { return token_; }
  // 0 before connect(); one more for each attempt.
  std::uint64_t attempt() const { return attempt_; }
  // True while a welcomed connection is lost and being resumed.
  bool resuming() const { return lost_since_ms_ != 0; }
  // True once resuming has failed for longer than the reconnect window.
  bool gone() const { return gone_; }
  // Where the room went (PROTOCOL.md 4.9b): "" until a `moved` came. A move starts a new
  // attempt at once, there, with the token (and the room's code, should the token not
  // be known there); the caller sends it to moved_to() (moves() counts the moves).
  const std::string& moved_to() const { return moved_to_; }
  std::uint64_t moves() const { return moves_; }

 private:
  ClientConfig config_;
  bool resume_when_lost_;
  ClientEndpoint endpoint_;
  std::string token_;
  std::uint64_t attempt_ = 0;
  std::uint64_t window_ms_ = 60000;
  std::uint64_t lost_since_ms_ = 0;
  bool welcomed_ = false;  // some attempt was welcomed: there is a player to resume
  bool gone_ = false;
  bool left_ = false;  // we said bye: not a lost connection
  std::string moved_to_;
  std::uint64_t moves_ = 0;
};

}  // namespace fts::protocol
