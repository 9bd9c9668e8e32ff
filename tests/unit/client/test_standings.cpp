// Issue 37, point 5: the standings rank by what a player earned in the match, not by
// coins in hand. A late joiner holds the median grant (1,767 coins) and earned nothing;
// a bot that earned 1,911 and spent it has 65 left: the bot is first, on the shop
// screen and at game over, and the title says what the order means.
#include <catch2/catch.hpp>

#include <string>

#include "seed_situation.hpp"
#include "ui/panel.hpp"
#include "ui/render.hpp"

using namespace fts::client;
using fts::protocol::Event;
using fts::protocol::EventKind;
using fts::protocol::Phase;
using fts::protocol::Snapshot;

namespace {

Snapshot two_players(Phase phase) {
  Snapshot s = fts::client::test::seed_snapshot(phase);
  s.players.clear();
  auto bot = fts::client::test::seed_player();
  bot.id = 1;
  bot.name = "shopper";
  bot.coins = 65;
  bot.lives = 1;
  auto late = fts::client::test::seed_player();
  late.id = 2;
  late.name = "latecomer";
  late.coins = 1767;
  late.lives = 3;
  s.players = {bot, late};
  return s;
}

// The row of the rendered screen that names `who`, or -1.
int row_of(const Screen& screen, const std::string& who) {
  for (std::size_t i = 0; i < screen.lines().size(); ++i)
    if (screen.lines()[i].find(who) != std::string::npos) return static_cast<int>(i);
  return -1;
}

bool has(const Screen& screen, const std::string& text) { return row_of(screen, text) >= 0; }

}  // namespace

TEST_CASE("Standings: ranked by coins earned, not by coins in hand (a late joiner's grant)", "[client][score]") {
  // The shop shows the standings where the slide leaves room (80x30 and up); game over at 80x24.
  const struct {
    Phase phase;
    TerminalSize size;
  } cases[] = {{Phase::shop, {80, 30}}, {Phase::shop, {120, 40}}, {Phase::over, {80, 24}}};
  for (const auto& [phase, size] : cases) {
    INFO((phase == Phase::shop ? "shop at " : "game over at ") << size.cols << "x" << size.rows);
    Snapshot s = two_players(phase);
    ViewState view;
    view.my_player_id = 2;
    view.color = false;
    // The bot's knocks over the match: 1,911 coins in all.
    tally_event(view.scores, Event{1, 10, EventKind::enemy_fell, 40, 1, 1000});
    tally_event(view.scores, Event{2, 20, EventKind::enemy_fell, 41, 1, 911});
    const Screen screen = render(s, s, 0, size, view);
    REQUIRE(has(screen, "by coins earned"));
    REQUIRE(has(screen, "Earned"));
    const int bot = row_of(screen, " 1 shopper");
    const int late = row_of(screen, " 2 latecomer*");
    CHECK(bot >= 0);
    CHECK(late >= 0);
    CHECK(bot < late);
    CHECK(screen.lines()[static_cast<std::size_t>(bot)].find("1,911") != std::string::npos);
  }
}

TEST_CASE("Standings: equal earnings fall back to coins in hand, then lives", "[client][score]") {
  Snapshot s = two_players(Phase::shop);
  ViewState view;
  view.my_player_id = 1;
  const auto board = scoreboard_lines(s, view, false);
  REQUIRE(board.size() == 4);
  CHECK(board[0] == "Standings after level " + std::to_string(s.level) + ", by coins earned");
  CHECK(board[2].find("latecomer") != std::string::npos);  // nobody earned: more coins first
  CHECK(board[3].find("shopper*") != std::string::npos);
}
