// The leaderboard on fts-client's screens (issue 41, PROTOCOL.md 4.7c): the waiting
// screen (the lobby) shows the server's top 10 (best level, ties by coins) and the
// player's own place; the level-end screen (the shop) shows the player's best. Names came
// from the server's database and are cleaned here again, like every name. Pure: the tests
// lay them out at 80x24 and 120x40.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ui/view.hpp"

namespace fts::client {

struct BoardLine {
  std::string text;   // printable ASCII, at most the columns asked for
  bool title = false; // the heading
  bool mine = false;  // the player's own row, or the line about the player
};

// The waiting screen's board in `cols` columns and at most `rows` rows: a heading, the
// top rows (as many as fit, at most 10) and the line about the player, which is kept
// first when rows are short. Empty when there is no board and nothing to say.
std::vector<BoardLine> board_lines(const ViewState& view, int cols, int rows);

// The line about the player: "You: #57 of 10,000, best level 3 (1,234 coins)", or why
// there is no place ("as a guest", "no match recorded yet").
std::string own_board_line(const ViewState& view);

// The level-end screen's line for a player who reached `level` in this match: "Your best:
// level 7 (#3 of 120)", "A new best: level 8 (was 7)"; "" without a board or as a guest.
std::string best_line(const ViewState& view, std::uint32_t level);

}  // namespace fts::client
