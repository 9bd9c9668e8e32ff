// The leaderboard on the client's screens (issue 41, PROTOCOL.md 4.7c): the waiting screen
// shows the top 10 and the player's place at 80x24 and at 120x40, whatever the names the
// server's database held; the level-end screen shows the player's best; a guest and a
// server without a board; --forget-me's question and answers.
#include <catch2/catch.hpp>

#include <string>

#include "seed_situation.hpp"
#include "ui/board.hpp"
#include "ui/forget.hpp"
#include "ui/panel.hpp"
#include "ui/render.hpp"

using namespace fts::client;
using fts::protocol::BoardRow;
using fts::protocol::Leaderboard;
using fts::protocol::Phase;
using fts::protocol::Snapshot;

namespace {

// Ten rows, names as a hostile database could hold them (a real server cleans them, and
// a board with such a name does not decode: the client cleans again all the same).
Leaderboard hostile_board() {
  Leaderboard b;
  b.cmd = 3;
  const std::vector<std::string> names = {
      "\x1b[2J\x1b]0;pwned\x07", "ann",   "\xe6\x97\xa5\xe6\x9c\xac", "\x7f\x08\x9b" "31m",
      "sixteen_letters_",        "bob",   "c",                        "d",
      "e",                       "frank"};
  for (std::uint32_t i = 0; i < 10; ++i)
    b.top.push_back(BoardRow{i + 1, names[i], 40 - static_cast<std::int64_t>(i), 1'000'000'000 - 1000 * i});
  b.of = 10'000;
  b.rank = 5'717;
  b.best = 3;
  b.best_coins = 1'234;
  return b;
}

ViewState lobby_view(const Leaderboard& b) {
  ViewState v = fts::client::test::plain_view();
  v.board = b;
  return v;
}

std::string screen_text(const Screen& s) {
  std::string out;
  for (const auto& l : s.lines()) out += l + "\n";
  return out;
}

bool printable(const std::string& text) {
  for (unsigned char c : text)
    if (c != '\n' && (c < 0x20 || c > 0x7E)) return false;
  return true;
}

}  // namespace

TEST_CASE("Board: the waiting screen shows the top 10 and your place, at 80x24 and 120x40", "[client][board]") {
  const Snapshot s = fts::client::test::seed_snapshot(Phase::lobby);
  const ViewState v = lobby_view(hostile_board());
  for (const TerminalSize size : {TerminalSize{80, 24}, TerminalSize{120, 40}}) {
    INFO(size.cols << "x" << size.rows);
    const Screen screen = render(s, s, 0, size, v);
    const std::string text = screen_text(screen);
    INFO(text);
    CHECK(printable(text));
    CHECK(text.find("Waiting for the match") != std::string::npos);
    CHECK(text.find("Best levels on this server (10,000 players)") != std::string::npos);
    for (int rank = 1; rank <= 10; ++rank) CHECK(text.find(std::to_string(rank) + ". ") != std::string::npos);
    CHECK(text.find("[2J]0;pwned") != std::string::npos);  // the escapes' remains, harmless
    CHECK(text.find(" 3. ??") != std::string::npos);        // two CJK characters, one '?' each
    CHECK(text.find(" 4. ?31m") != std::string::npos);      // DEL, BS gone, C1 CSI a '?'
    CHECK(text.find("sixteen_letters_") != std::string::npos);
    CHECK(text.find("level 40") != std::string::npos);
    CHECK(text.find("1,000,000,000 coins") != std::string::npos);
    CHECK(text.find("You: #5,717 of 10,000, best level 3 (1,234 coins)") != std::string::npos);
    // Every row inside the frame: none runs past the platform's columns.
    const FrameLayout L = frame_layout(size, v, s);
    for (int row = 0; row < size.rows; ++row) {
      const std::string line = screen.line(row);
      const auto at = line.find("Best levels");
      if (at != std::string::npos) CHECK(static_cast<int>(at) >= L.arena.col0);
    }
  }
}

TEST_CASE("Board: the board's lines fit the columns and keep your line when rows are short", "[client][board]") {
  const ViewState v = lobby_view(hostile_board());
  const auto lines = board_lines(v, 200, 100);
  REQUIRE(lines.size() == 12);  // heading, 10 rows, you
  CHECK(lines.front().title);
  CHECK(lines.back().mine);
  CHECK(lines.back().text.find("#5,717") != std::string::npos);
  for (const int cols : {20, 40, 57}) {
    for (const auto& l : board_lines(v, cols, 100)) {
      CHECK(static_cast<int>(l.text.size()) <= cols);
      CHECK(printable(l.text));
    }
  }
  const auto short_rows = board_lines(v, 80, 5);
  REQUIRE(short_rows.size() == 5);  // heading, 3 rows, you
  CHECK(short_rows.back().mine);
  CHECK(board_lines(v, 80, 1).size() == 1);
  CHECK(board_lines(v, 80, 1).front().mine);
  CHECK(board_lines(v, 80, 0).empty());
  // Your own row is marked when you are in the top 10.
  Leaderboard top = hostile_board();
  top.rank = 2;
  const auto mine = board_lines(lobby_view(top), 80, 20);
  CHECK(mine[2].mine);
  CHECK_FALSE(mine[1].mine);
}

TEST_CASE("Board: a guest, a player without a match, an empty board, no board", "[client][board]") {
  const Snapshot s = fts::client::test::seed_snapshot(Phase::lobby);
  ViewState guest = lobby_view(hostile_board());
  guest.board->rank = 0;
  guest.guest = true;
  CHECK(screen_text(render(s, s, 0, {80, 24}, guest)).find("You play as a guest: nothing is recorded.") !=
        std::string::npos);
  ViewState fresh = lobby_view(hostile_board());
  fresh.board->rank = 0;
  CHECK(own_board_line(fresh).find("no match recorded yet") != std::string::npos);
  ViewState empty = lobby_view(Leaderboard{1, {}, 0, 0, 0, 0});
  const std::string text = screen_text(render(s, s, 0, {80, 24}, empty));
  CHECK(text.find("(0 players)") != std::string::npos);
  CHECK(text.find("No match recorded yet.") != std::string::npos);
  // No board (a server without profiles): the waiting screen as before it.
  ViewState none = fts::client::test::plain_view();
  const std::string before = screen_text(render(s, s, 0, {80, 24}, none));
  CHECK(before.find("Waiting for the match") != std::string::npos);
  CHECK(before.find("Best levels") == std::string::npos);
  none.board_note = "Leaderboard: the server's profile database is not available now: try again later.";
  CHECK(screen_text(render(s, s, 0, {120, 40}, none)).find("Leaderboard: the server's profile") != std::string::npos);
}

TEST_CASE("Board: the level-end screen shows your best", "[client][board]") {
  Snapshot s = fts::client::test::seed_snapshot(Phase::shop);  // level 3 complete
  ViewState v = lobby_view(hostile_board());       // best level 3, #5,717
  for (const TerminalSize size : {TerminalSize{80, 24}, TerminalSize{120, 40}}) {
    INFO(size.cols << "x" << size.rows);
    const std::string text = screen_text(render(s, s, 0, size, v));
    INFO(text);
    CHECK(text.find("Your best: level 3 (#5,717 of 10,000)") != std::string::npos);
    CHECK(text.find("Level 3 Complete") != std::string::npos);
  }
  s.level = 4;
  CHECK(best_line(v, 4) == "A new best: level 4 (was 3)");
  CHECK(screen_text(render(s, s, 0, {80, 24}, v)).find("A new best: level 4 (was 3)") != std::string::npos);
  // Out of lives: the line under the heading.
  s.players[0].lives = 0;
  s.players[0].alive = false;
  CHECK(screen_text(render(s, s, 0, {80, 24}, v)).find("A new best: level 4") != std::string::npos);
  v.guest = true;
  CHECK(best_line(v, 4).empty());
  v.guest = false;
  v.board->rank = 0;
  CHECK(best_line(v, 2) == "Your first match: level 2 so far");
  v.board.reset();
  CHECK(best_line(v, 2).empty());
}

TEST_CASE("Board: the game-over screen shows your place under the standings", "[client][board]") {
  Snapshot s = fts::client::test::seed_snapshot(Phase::over);
  const ViewState v = lobby_view(hostile_board());
  for (const TerminalSize size : {TerminalSize{80, 24}, TerminalSize{120, 40}}) {
    INFO(size.cols << "x" << size.rows);
    const std::string text = screen_text(render(s, s, 0, size, v));
    INFO(text);
    CHECK(text.find("GAME OVER") != std::string::npos);
    CHECK(text.find("Press Enter to play again") != std::string::npos);
    CHECK(text.find("You: #5,717 of 10,000, best level 3 (1,234 coins)") != std::string::npos);
  }
  // No board: the screen as before it.
  const std::string none = screen_text(render(s, s, 0, {80, 24}, fts::client::test::plain_view()));
  CHECK(none.find("You: #") == std::string::npos);
}

TEST_CASE("Forget me (--forget-me): asked first, yes confirms, the answer in words", "[client][forget]") {
  const std::string q = forget_prompt("127.0.0.1:7777", "0e934e02183f97e0cd83ad10d6c4be5a", "/home/ann/.local/state/x");
  CHECK(q.find("0e934e02183f97e0cd83ad10d6c4be5a") != std::string::npos);
  CHECK(q.find("Type yes") != std::string::npos);
  CHECK(forget_confirmed("yes"));
  CHECK(forget_confirmed("  YES \r"));
  CHECK_FALSE(forget_confirmed("y"));
  CHECK_FALSE(forget_confirmed(""));
  CHECK_FALSE(forget_confirmed("yes please"));
  const auto ok = forget_outcome({1, 1, true, "ok", "your profile is erased: its records are gone"}, "/id");
  CHECK(ok.erased);
  CHECK(ok.text.find("your profile is erased") == 0);
  CHECK(ok.text.find("/id is kept") != std::string::npos);
  const auto guest = forget_outcome({1, 1, false, "guest", "x"}, "/id");
  CHECK_FALSE(guest.erased);
  CHECK(guest.text == "not erased: you play as a guest: there is no profile to erase.");
  const auto hostile = forget_outcome({1, 1, true, "ok", "\x1b]0;t\x07gone"}, "/id");
  CHECK(printable(hostile.text));
}
