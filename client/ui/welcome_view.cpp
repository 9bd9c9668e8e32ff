#include "ui/welcome_view.hpp"

#include "ui/sanitize.hpp"
#include "ui/start_screen.hpp"

namespace fts::client {

void show_welcome(ViewState& view, const protocol::Welcome& w) {
  view.my_player_id = w.player_id;
  view.arena_width_u = w.match.arena_width_u;
  view.arena_height_u = w.match.arena_height_u;
  view.shop_terms = w.shop();
  view.tick_rate_hz = w.tick_rate_hz();
  view.room = room_label(sanitize(w.room, 8), w.spectator);  // as the log shows the code
}

std::uint64_t reconnect_window_s(const std::optional<protocol::Welcome>& w) {
  return (w ? w->reconnect_window_ms : 60000) / 1000;
}

double tick_rate_hz(const std::optional<protocol::Welcome>& w) {
  return w ? w->tick_rate_hz() : 100.0;
}

}  // namespace fts::client
