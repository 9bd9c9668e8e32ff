// Quick chat on the server: a line a player says is cleaned (printable ASCII, cut to a
// length), rate-limited per player (a token bucket) and then relayed to every connected
// player by the host. The rooms work moves one relay into each room; the console's
// announce sends the same protocol Chat with from = 0 and name "host".
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "fts/protocol/codes.hpp"

namespace fts::server {

struct ChatLimits {
  std::size_t max_chars = 120;     // longer lines are cut
  double burst_lines = 5;          // a player may say this many lines at once...
  std::uint64_t refill_ms = 2000;  // ...and one more per this many ms
  std::size_t max_tracked = 256;   // players with a bucket; full buckets are forgotten beyond it
};

struct ChatVerdict {
  bool ok = false;
  protocol::ResultCode code = protocol::ResultCode::ok;  // ok, rate (too many lines), empty (nothing printable)
  std::string text;  // the cleaned line (ok only)
};

class ChatRelay {
 public:
  explicit ChatRelay(ChatLimits limits = {}) : limits_(limits) {}
  // A line `player_id` says at now_ms: accepted (cleaned) or refused with a code.
  ChatVerdict accept(std::uint32_t player_id, std::string_view text, std::uint64_t now_ms);
  // Printable ASCII only (controls dropped, other bytes '?'), spaces collapsed, trimmed,
  // cut to max_chars.
  static std::string clean(std::string_view text, std::size_t max_chars);

 private:
  struct Bucket {
    double tokens = 0;
    std::uint64_t at_ms = 0;
  };
  ChatLimits limits_;
  std::map<std::uint32_t, Bucket> buckets_;
};

}  // namespace fts::server
