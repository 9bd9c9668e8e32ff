#include "fts/protocol/connection.hpp"

namespace fts::protocol {

ClientConnection::ClientConnection(ClientConfig config, bool resume_when_lost)
    : config_(std::move(config)), resume_when_lost_(resume_when_lost), endpoint_(config_), token_(config_.token) {}

void ClientConnection::connect(std::uint64_t now_ms) {
  ClientConfig c = config_;
  c.token = token_;
  endpoint_ = ClientEndpoint(c);
  endpoint_.connect(now_ms);
  ++attempt_;
  left_ = false;
}

void ClientConnection::leave(std::uint64_t now_ms, const std::string& reason) {
  endpoint_.disconnect(now_ms, reason);
  left_ = true;
}

void ClientConnection::update(std::uint64_t now_ms) {
  endpoint_.update(now_ms);
  const ClientState st = endpoint_.state();
  if (st == ClientState::connected && endpoint_.welcome()) {
    token_ = endpoint_.welcome()->token;
    window_ms_ = endpoint_.welcome()->reconnect_window_ms;
    welcomed_ = true;
    lost_since_ms_ = 0;
    return;
  }
  if (const auto& moved = endpoint_.moved(); moved && !left_ && welcomed_) {
    moved_to_ = moved->address;
    ++moves_;
    // A spectator watches on there (its session is not in the room's journal, so it comes
    // as a new spectator); a player's token takes it back, else it joins by the code.
    if (config_.join != "spectate") config_.join = "join";
    else token_.clear();
    config_.room = moved->room;
    lost_since_ms_ = 0;
    connect(now_ms);
    return;
  }
  if (!resume_when_lost_ || !welcomed_ || gone_ || left_) return;
  if (st != ClientState::timed_out && st != ClientState::disconnected) return;
  if (lost_since_ms_ == 0) lost_since_ms_ = now_ms;
  if (now_ms - lost_since_ms_ > window_ms_) {
    gone_ = true;
    return;
  }
  connect(now_ms);
}

}  // namespace fts::protocol
