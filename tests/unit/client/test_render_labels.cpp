// Issue 26 (4): names on the field go next to their own ball and never over a ball, the
// frame or another name; your ball is always marked; the HUD keeps the room code at the
// smallest size.
#include <catch2/catch.hpp>

#include <cctype>
#include <string>

#include "field_geometry.hpp"
#include "seed_situation.hpp"
#include "ui/panel.hpp"
#include "ui/render.hpp"

using namespace fts::client;
using fts::protocol::BallKind;
using fts::protocol::BallState;
using fts::protocol::Phase;
using fts::protocol::Snapshot;

namespace {

BallState label_ball(std::uint32_t id, double x, double y, BallKind kind, std::uint32_t owner = 0) {
  const bool enemy = kind == BallKind::enemy;
  return fts::client::test::make_ball(id, x, y, kind, owner, enemy ? 34 : 40, enemy ? 15 : 16);
}

// Six players (lower-case names: any letter on a ball or the frame is a name) and four
// enemies: you in the middle under an enemy, bob against the top edge, cleo against the
// left edge, dora on the bottom edge, eve and fay side by side.
Snapshot crowded() {
  Snapshot s = fts::client::test::seed_snapshot(Phase::play);
  s.players.clear();
  const char* names[] = {"ann", "bob", "cleo", "dora", "eve", "fay"};
  for (std::uint32_t i = 0; i < 6; ++i) {
    auto p = fts::client::test::seed_player();
    p.id = i + 1;
    p.name = names[i];
    s.players.push_back(p);
  }
  s.balls = {label_ball(1, 250, 150, BallKind::player, 1), label_ball(2, 100, 292, BallKind::player, 2),
             label_ball(3, 8, 150, BallKind::player, 3),   label_ball(4, 400, 6, BallKind::player, 4),
             label_ball(5, 380, 150, BallKind::player, 5), label_ball(6, 412, 150, BallKind::player, 6),
             label_ball(7, 250, 195, BallKind::enemy),     label_ball(8, 120, 250, BallKind::enemy),
             label_ball(9, 300, 60, BallKind::enemy),      label_ball(10, 100, 255, BallKind::enemy)};
  return s;
}

bool ball_char(char c) {
  return c == kMyBallChar || c == kPlayerBallChar || c == kEnemyBallChar || c == kRocketChar ||
         std::isdigit(static_cast<unsigned char>(c));
}

bool adjacent(int c0, int r0, int c1, int r1) { return std::abs(c0 - c1) + std::abs(r0 - r1) == 1; }

}  // namespace

TEST_CASE("names never cover a ball or the frame", "[client][render][labels]") {
  const Snapshot s = crowded();
  for (const TerminalSize size : {TerminalSize{60, 20}, TerminalSize{80, 24}, TerminalSize{120, 40}, TerminalSize{200, 60}}) {
    INFO(size.cols << "x" << size.rows);
    const Screen screen = render(s, s, 0, size, fts::client::test::plain_view());
    const Viewport v = arena_viewport(size, fts::client::test::plain_view(), s);
    for (const auto& b : s.balls) {
      for (const auto& [col, row] : fts::client::test::disc_cells(v, b)) {
        INFO("ball " << b.id << " cell " << col << "," << row << ": " << screen.line(row));
        CHECK(ball_char(screen.at(col, row).ch));
      }
    }
    for (int col = v.col0 - 1; col <= v.col0 + v.cols; ++col) {
      for (const int row : {v.row0 - 1, v.row0 + v.rows}) {
        INFO("frame " << col << "," << row << ": " << screen.line(row));
        const char c = screen.at(col, row).ch;
        CHECK((c == '+' || c == '-' || ball_char(c)));
      }
    }
    for (int row = v.row0; row < v.row0 + v.rows; ++row) {
      for (const int col : {v.col0 - 1, v.col0 + v.cols}) {
        INFO("frame " << col << "," << row << ": " << screen.line(row));
        const char c = screen.at(col, row).ch;
        CHECK((c == '|' || ball_char(c)));
      }
    }
  }
}

TEST_CASE("a name sits next to its own ball, at the edges too", "[client][render][labels]") {
  const Snapshot s = crowded();
  for (const TerminalSize size : {TerminalSize{60, 20}, TerminalSize{80, 24}, TerminalSize{120, 40}, TerminalSize{200, 60}}) {
    const Screen screen = render(s, s, 0, size, fts::client::test::plain_view());
    const Viewport v = arena_viewport(size, fts::client::test::plain_view(), s);
    for (const auto& b : s.balls) {
      if (b.kind != BallKind::player) continue;
      const std::string name = s.players[b.owner - 1].name;
      INFO(size.cols << "x" << size.rows << " " << name);
      // Some whole occurrence of the name on the platform touches one of the ball's cells.
      const auto cells = fts::client::test::disc_cells(v, b);
      bool beside = false;
      for (int row = v.row0; row < v.row0 + v.rows; ++row) {
        const std::string line = screen.line(row);
        for (auto at = line.find(name); at != std::string::npos; at = line.find(name, at + 1)) {
          const int start = static_cast<int>(at), end = start + static_cast<int>(name.size());
          if (start < v.col0 || end > v.col0 + v.cols) continue;
          if (std::islower(static_cast<unsigned char>(line[at - 1])) ||
              std::islower(static_cast<unsigned char>(line[static_cast<std::size_t>(end)])))
            continue;  // part of another word
          for (int col = start; col < end; ++col)
            for (const auto& [bc, br] : cells) beside = beside || adjacent(col, row, bc, br);
        }
      }
      CAPTURE(screen.line(fts::client::test::top_row(v, b) - 1), screen.line(fts::client::test::top_row(v, b)));
      CHECK(beside);
    }
  }
}

TEST_CASE("at 60x20 your ball keeps its '@' and the HUD its room code", "[client][render][labels][hud]") {
  Snapshot s = crowded();
  s.players[0].coins = 1'234'567;
  for (const char* name : {"charlotte", "sixteen_letters_"}) {  // a third legend row: a smaller platform
    auto p = fts::client::test::seed_player();
    p.id = static_cast<std::uint32_t>(s.players.size() + 1);
    p.name = name;
    s.players.push_back(p);
  }
  ViewState view = fts::client::test::plain_view();
  view.ping_ms = 123;
  view.loss_percent = 12.5;
  view.room = "Room KXBQT";
  const TerminalSize size{60, 20};
  const Viewport v = arena_viewport(size, view, s);
  // Your ball two cells wide and one row tall here: its mass would fill it.
  const int mid_col = v.col0 + v.cols / 2;
  s.balls[0].x = v.x_of(mid_col) + 0.45 * v.units_per_col();
  s.balls[0].y = v.y_of(v.row0 + v.rows / 2);
  REQUIRE(fts::client::test::disc_cells(v, s.balls[0]).size() == 2);
  Screen screen = render(s, s, 0, size, view);
  bool marked = false;
  for (const auto& [col, row] : fts::client::test::disc_cells(v, s.balls[0])) marked = marked || screen.at(col, row).ch == kMyBallChar;
  CHECK(marked);
  CHECK(screen.line(0).find("Room KXBQT") != std::string::npos);
  CHECK(screen.line(0).find("1,234,567") != std::string::npos);  // shortened, not dropped
  // A status on the HUD's row leaves the room code too; so does a spectator's.
  view.status = "connection lost, reconnecting...";
  screen = render(s, s, 0, size, view);
  CHECK(screen.line(0).find("Room KXBQT") != std::string::npos);
  CHECK(screen.line(0).find("connection lost, reconnecting...") != std::string::npos);
  view.status.clear();
  view.room = "Watching KXBQT";
  view.my_player_id = 0;
  CHECK(render(s, s, 0, size, view).line(0).find("Watching KXBQT") != std::string::npos);
  for (int cols = 60; cols <= 200; ++cols) {
    INFO(cols);
    const std::string hud = hud_fit(s, fts::client::test::plain_view(), cols);
    CHECK(static_cast<int>(hud.size()) <= cols);
  }
}

TEST_CASE("a tiny ball of yours is '@' and shows no mass over it", "[client][render][labels]") {
  Snapshot s = crowded();
  s.balls[0].radius = 3;  // one or two cells at 80x24
  const TerminalSize size{80, 24};
  const Viewport v = arena_viewport(size, fts::client::test::plain_view(), s);
  const Screen screen = render(s, s, 0, size, fts::client::test::plain_view());
  bool marked = false;
  for (const auto& [col, row] : fts::client::test::disc_cells(v, s.balls[0])) marked = marked || screen.at(col, row).ch == kMyBallChar;
  CHECK(marked);
}
