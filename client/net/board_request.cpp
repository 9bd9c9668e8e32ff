#include "net/board_request.hpp"

namespace fts::client {

void BoardRequest::ask(protocol::ClientEndpoint& endpoint, std::uint64_t now_ms, int tries) {
  if (rid_ != 0 || endpoint.state() != protocol::ClientState::connected) return;
  rid_ = endpoint.send_command(protocol::CommandOp::top, 0, now_ms);
  ok_ms_ = 0;
  tries_ = tries;
}

bool BoardRequest::answered_by(const protocol::Leaderboard& board) {
  if (rid_ == 0 || board.cmd != rid_) return false;  // an older request's
  rid_ = 0;
  return true;
}

bool BoardRequest::take_result(const protocol::Result& result, std::uint64_t now_ms) {
  if (rid_ == 0 || result.command_rid != rid_) return false;
  if (result.ok) ok_ms_ = now_ms;
  else rid_ = 0;
  return true;
}

void BoardRequest::retry_if_lost(protocol::ClientEndpoint& endpoint, std::uint64_t now_ms) {
  if (rid_ == 0 || ok_ms_ == 0 || now_ms - ok_ms_ <= kWaitMs) return;
  rid_ = 0;
  if (tries_ < kTries) ask(endpoint, now_ms, tries_ + 1);
}

}  // namespace fts::client
