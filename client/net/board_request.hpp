// The leaderboard fts-client asks the server for (`cmd top`, PROTOCOL.md 4.7c): one
// request on its way at a time. Its result comes first and the board after it; a board
// answered `ok` but lost on the way is not resent, so after kWaitMs without it the board
// is asked again, up to kTries times. A new session forgets the request (its rids start
// again).
#pragma once

#include <cstdint>

#include "fts/protocol/client.hpp"

namespace fts::client {

class BoardRequest {
 public:
  static constexpr std::uint64_t kWaitMs = 1500;
  static constexpr int kTries = 3;

  // Asks, unless a request is on its way or the endpoint is not connected.
  void ask(protocol::ClientEndpoint& endpoint, std::uint64_t now_ms, int tries = 0);
  void forget() { rid_ = 0; }
  // Whether `board` answers the request on its way (which then is done).
  bool answered_by(const protocol::Leaderboard& board);
  // Whether `result` is the request's own; a refusal ends the request.
  bool take_result(const protocol::Result& result, std::uint64_t now_ms);
  // Asks again when the result said ok and the board has not come within kWaitMs.
  void retry_if_lost(protocol::ClientEndpoint& endpoint, std::uint64_t now_ms);

 private:
  std::uint32_t rid_ = 0;     // the request on its way (0: none)
  std::uint64_t ok_ms_ = 0;   // when its result said ok (the board follows)
  int tries_ = 0;
};

}  // namespace fts::client
