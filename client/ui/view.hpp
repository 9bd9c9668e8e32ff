// What the renderer needs besides the snapshots: who we are, the connection's health, the
// message log, the chat line being typed, who is being watched and the score book.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fts/protocol/messages.hpp"
#include "fts/sim/items.hpp"

namespace fts::client {

// One line of the message log. `from` colours the first `prefix_chars` characters (the
// sender's name of a chat line) in that player's colour; 0: no sender.
struct LogLine {
  LogLine() = default;
  LogLine(std::string text_, std::uint64_t at_ms_, std::uint32_t from_ = 0, std::size_t prefix_chars_ = 0,
          bool host_ = false)
      : text(std::move(text_)), at_ms(at_ms_), from(from_), prefix_chars(prefix_chars_), host(host_) {}
  std::string text;  // already sanitised
  std::uint64_t at_ms = 0;
  std::uint32_t from = 0;
  std::size_t prefix_chars = 0;
  bool host = false;  // from the host (console announce): shown in the title style
};

// One player's tally as the client counts it from the events it sees.
struct Score {
  std::int64_t coins_level = 0;  // coins from enemies knocked off this level
  std::int64_t coins_total = 0;  // the same, over the whole match
  std::int64_t knocks_level = 0, knocks_total = 0;
  bool operator==(const Score&) const = default;
};

struct ViewState {
  std::uint32_t my_player_id = 0;
  double arena_width_u = 500, arena_height_u = 300;
  double ping_ms = -1;       // < 0: unknown
  double loss_percent = -1;  // snapshots lost, < 0: unknown
  int delay_ms = -1;         // other balls drawn this far behind the server (< 0: not shown)
  int thrust_x = 0, thrust_y = 0;  // the own ball's thrust this frame (drawn as its exhaust)
  std::string status;        // e.g. "connection lost, reconnecting..." (shown in red)
  std::vector<LogLine> messages;  // the message log, newest last (bounded by the client)
  std::uint64_t now_ms = 0;       // for the ages of the log lines
  std::string shop_result;   // the outcome of the last purchase (already sanitised)
  std::uint64_t shop_result_ms = 0;  // when it came (shown kShopResultShowMs, ui/render.hpp)
  // A moment's word in the footer ("Room moved to another server"), whatever the log
  // shows meanwhile: shown kNoticeShowMs (ui/panel.hpp) from notice_ms, in place of the keys.
  std::string notice;
  std::uint64_t notice_ms = 0;
  bool color = true;
  bool fine = false;  // the field in braille dots (ui/fine_field.hpp), with colour only
  sim::ShopTerms shop_terms;  // the server's, from its welcome
  double tick_rate_hz = 100;  // the server's, from its welcome (countdowns)
  std::map<std::uint32_t, std::string> names;  // every player seen (names of those who left)
  std::map<std::uint32_t, Score> scores;       // by player id
  std::uint32_t follow_id = 0;  // the player watched (Tab), 0: none
  bool chat_open = false;       // `t` was pressed: the chat line is being typed
  std::string chat_draft;
  bool mouse_steering = false;  // the pointer steers (shown in the footer)
  std::string replay_footer;    // --replay: the footer text (speed, pause, keys)
  std::string room;           // "Room ABCDE" / "Watching ABCDE" (ui/start_screen.hpp), "" : none
  // The leaderboard (PROTOCOL.md 4.7c, ui/board.hpp): the last one the server sent (names
  // as they came: cleaned when drawn), shown on the waiting screen and, as the player's
  // best, after each level.
  std::optional<protocol::Leaderboard> board;
  bool guest = false;       // we play without an identity: no rank of our own
  std::string board_note;   // why there is no board (already sanitised), "" : nothing to say
};

}  // namespace fts::client
