#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "seed_situation.hpp"
#include "ui/render.hpp"

using namespace fts::client;
using fts::protocol::BallKind;
using fts::protocol::BallState;
using fts::protocol::Phase;
using fts::protocol::Snapshot;

namespace {

BallState ball(std::uint32_t id, double x, double y, BallKind kind, std::uint32_t owner = 0, double mass = 40) {
  return fts::client::test::make_ball(id, x, y, kind, owner, mass, 11 + std::floor(mass / 8));
}

}  // namespace

TEST_CASE("the platform keeps its aspect ratio at several terminal sizes", "[client][render]") {
  const TerminalSize sizes[] = {{80, 24}, {120, 40}, {200, 50}, {60, 60}, {300, 30}, {60, 20}};
  for (const auto size : sizes) {
    const Viewport v = arena_viewport(size, fts::client::test::plain_view());
    INFO(size.cols << "x" << size.rows << " -> " << v.cols << "x" << v.rows);
    // A cell is twice as tall as wide: 500 x 300 u wants cols / (2 rows) = 5 / 3.
    const double ratio = v.cols / (kCellAspect * v.rows);
    const double tolerance = 5.0 / 3.0 * (1.0 / v.cols + 1.0 / v.rows) + 1e-9;
    CHECK(std::abs(ratio - 5.0 / 3.0) <= tolerance);
    // It fits inside its frame, between the text rows, and fills one dimension.
    CHECK(v.col0 >= 1);
    CHECK(v.col0 + v.cols <= size.cols - 1);
    CHECK(v.row0 >= 2);  // below the HUD and the frame's top
    CHECK(v.row0 + v.rows <= size.rows - 2);  // above the frame's bottom and the footer
    // It takes the room left by the HUD, the legend, the log and the footer.
    CHECK((v.cols >= size.cols / 2 || v.rows >= size.rows / 2));
  }
}

TEST_CASE("balls at the platform's corners land in the corner cells", "[client][render]") {
  const TerminalSize size{120, 40};
  const Viewport v = arena_viewport(size, fts::client::test::plain_view());
  Snapshot s = fts::client::test::seed_snapshot(Phase::play);
  s.balls = {ball(1, 0.01, 0.01, BallKind::enemy, 0, 5), ball(2, 499.99, 0.01, BallKind::enemy, 0, 5),
             ball(3, 0.01, 299.99, BallKind::enemy, 0, 5), ball(4, 499.99, 299.99, BallKind::enemy, 0, 5)};
  const Screen screen = render(s, s, 0, size, fts::client::test::plain_view());
  const int left = v.col0, right = v.col0 + v.cols - 1, top = v.row0, bottom = v.row0 + v.rows - 1;
  CHECK(v.col_of(0.01) == left);
  CHECK(v.col_of(499.99) == right);
  CHECK(v.row_of(299.99) == top);
  CHECK(v.row_of(0.01) == bottom);
  // The mass label "5" sits on each ball's centre cell.
  CHECK(screen.at(left, bottom).ch == '5');
  CHECK(screen.at(right, bottom).ch == '5');
  CHECK(screen.at(left, top).ch == '5');
  CHECK(screen.at(right, top).ch == '5');
  // Without balls, the frame's corners sit just outside the platform's corner cells.
  s.balls.clear();
  const Screen empty = render(s, s, 0, size, fts::client::test::plain_view());
  CHECK(empty.at(left - 1, top - 1).ch == '+');
  CHECK(empty.at(right + 1, bottom + 1).ch == '+');
  CHECK(empty.at(left, top).ch == kPlatformChar);
  CHECK(empty.at(right, bottom).ch == kPlatformChar);
  CHECK(empty.at(right + 2, bottom).ch == ' ');
}

TEST_CASE("balls are drawn at their positions with their mass, yours distinct", "[client][render]") {
  const TerminalSize size{120, 40};
  const Viewport v = arena_viewport(size, fts::client::test::plain_view());
  Snapshot s = fts::client::test::seed_snapshot(Phase::play);
  s.balls = {ball(1, 100, 150, BallKind::player, 1, 40), ball(2, 250, 150, BallKind::enemy, 0, 36),
             ball(3, 400, 150, BallKind::player, 2, 41), ball(4, 250, 60, BallKind::rocket, 1, 5)};
  s.balls[3].radius = 3;
  const Screen screen = render(s, s, 0, size, fts::client::test::plain_view());
  const int row = v.row_of(150);
  CHECK(screen.line(row).substr(static_cast<std::size_t>(v.col_of(100)), 2) == "40");
  CHECK(screen.line(row).substr(static_cast<std::size_t>(v.col_of(250)), 2) == "36");
  CHECK(screen.line(row).substr(static_cast<std::size_t>(v.col_of(400)), 2) == "41");
  CHECK(screen.at(v.col_of(100) - 2, row).ch == kMyBallChar);
  CHECK(screen.at(v.col_of(250) - 2, row).ch == kEnemyBallChar);
  CHECK(screen.at(v.col_of(400) - 2, row).ch == kPlayerBallChar);
  CHECK(screen.at(v.col_of(250), v.row_of(60)).ch == kRocketChar);
  // A ball of radius 16 u is about 7 cells wide and 4 rows tall at this size.
  int width = 0;
  for (int c = v.col0; c < v.col0 + v.cols; ++c)
    if (screen.at(c, row).ch == kMyBallChar || std::isdigit(static_cast<unsigned char>(screen.at(c, row).ch))) {
      if (c < v.col_of(175)) ++width;
    }
  CHECK(std::abs(width - 2 * 16 / v.units_per_col()) <= 2);
  // Empty platform is dotted; outside the frame is blank.
  CHECK(screen.at(v.col_of(250), v.row_of(250)).ch == kPlatformChar);
}

TEST_CASE("colour output follows NO_COLOR", "[client][render]") {
  CHECK(color_wanted(nullptr, "xterm-256color"));
  CHECK_FALSE(color_wanted("1", "xterm"));
  CHECK(color_wanted("", "xterm"));
  CHECK_FALSE(color_wanted(nullptr, "dumb"));
  Snapshot s = fts::client::test::seed_snapshot(Phase::play);
  s.balls = {ball(1, 100, 150, BallKind::player, 1, 40)};
  const Screen screen = render(s, s, 0, {80, 24}, fts::client::test::plain_view());
  const std::string plain = to_ansi(screen, false);
  const std::string coloured = to_ansi(screen, true);
  CHECK(plain.find("\x1b[0;") == std::string::npos);
  CHECK(coloured.find("\x1b[0;1;33m") != std::string::npos);  // your ball: bold yellow
}

TEST_CASE("game over and lobby overlays", "[client][render]") {
  Snapshot s = fts::client::test::seed_snapshot(Phase::over);
  const Screen screen = render(s, s, 0, {80, 24}, fts::client::test::plain_view());
  bool over = false;
  for (const auto& l : screen.lines()) over = over || l.find("GAME OVER at level 3") != std::string::npos;
  CHECK(over);
  CHECK(screen.line(23).rfind("Game over   Play again: Enter   Chat: t   Quit: q", 0) == 0);
  s.phase = Phase::lobby;
  s.players[0].ready = true;
  bool lobby = false;
  for (const auto& l : render(s, s, 0, {80, 24}, fts::client::test::plain_view()).lines()) lobby = lobby || l.find("Ready: ann (ready)") != std::string::npos;
  CHECK(lobby);
}

TEST_CASE("tiny and odd terminals and hostile numbers draw without harm", "[client][render]") {
  Snapshot s = fts::client::test::seed_snapshot(Phase::play);
  s.balls = {ball(1, 100, 150, BallKind::player, 1, 40), ball(2, -50, 400, BallKind::enemy, 0, 36),
             ball(3, 1e300, -1e300, BallKind::enemy, 0, 1e12), ball(4, std::nan(""), 5, BallKind::rocket)};
  s.balls[2].radius = 1e200;
  s.balls[1].mass = std::nan("");
  s.players[0].mass = std::numeric_limits<double>::infinity();
  ViewState odd = fts::client::test::plain_view();
  odd.arena_width_u = std::nan("");
  odd.arena_height_u = -4;
  CHECK(arena_viewport({80, 24}, odd).cols > 10);
  const TerminalSize sizes[] = {{1, 1}, {5, 3}, {20, 6}, {0, 0}, {-3, 7}, {400, 100}};
  for (const auto size : sizes) {
    for (Phase phase : {Phase::play, Phase::shop, Phase::lobby, Phase::over}) {
      s.phase = phase;
      const Screen screen = render(s, s, 0.5, size, fts::client::test::plain_view());
      CHECK(screen.cols() >= 1);
      CHECK(screen.rows() >= 1);
      CHECK_FALSE(to_ansi(screen, true).empty());
    }
  }
}
