// What the renderer needs besides the snapshots: who we are and the connection's health.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fts/sim/items.hpp"

namespace fts::client {

struct ViewState {
  std::uint32_t my_player_id = 0;
  double arena_width_u = 500, arena_height_u = 300;
  double ping_ms = -1;       // < 0: unknown
  double loss_percent = -1;  // snapshots lost, < 0: unknown
  std::string status;        // e.g. "connection lost, reconnecting..." (shown in red)
  std::vector<std::string> messages;  // recent happenings, newest last (already sanitised)
  std::string shop_result;   // the outcome of the last purchase (already sanitised)
  bool color = true;
  sim::ShopTerms shop_terms;  // the server's, from its welcome
  double tick_rate_hz = 100;  // the server's, from its welcome (countdowns)
  std::string room;           // "Room ABCDE" / "Watching ABCDE" (ui/start_screen.hpp), "" : none
};

}  // namespace fts::client
