// The field drawn finer (issue 37): braille dots with colour at 80x24 and 120x40, balls
// round and apart, moving in steps smaller than a cell; ASCII kept where the terminal
// cannot show them.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <string>

#include "seed_situation.hpp"
#include "ui/fine_field.hpp"
#include "ui/panel.hpp"
#include "ui/render.hpp"

using namespace fts::client;
using fts::protocol::BallKind;
using fts::protocol::BallState;
using fts::protocol::Phase;
using fts::protocol::Snapshot;

namespace {

BallState fine_ball(std::uint32_t id, double x, double y, BallKind kind, std::uint32_t owner, double radius, double mass = 40) {
  return fts::client::test::make_ball(id, x, y, kind, owner, mass, radius);
}

ViewState fine_view() {
  ViewState v;
  v.my_player_id = 1;
  v.color = true;
  v.fine = true;
  return v;
}

// Whether the dot (i, j) of the platform (dot 0 is the platform's first) is lit.
bool lit(const Screen& s, const Viewport& v, int i, int j) {
  const int col = v.col0 + static_cast<int>(std::floor(i / double(kDotsPerCol)));
  const int row = v.row0 + static_cast<int>(std::floor(j / double(kDotsPerRow)));
  if (!s.inside(col, row)) return false;
  const Cell& c = s.at(col, row);
  if (!c.braille()) return c.ch >= '0' && c.ch <= '9';  // a mass label sits on whole cells
  const int x = ((i % kDotsPerCol) + kDotsPerCol) % kDotsPerCol, y = ((j % kDotsPerRow) + kDotsPerRow) % kDotsPerRow;
  return (c.dots & braille_bit(x, y)) != 0;
}

int dot_i(const Viewport& v, double x) { return static_cast<int>(std::floor(x / (v.units_per_col() / kDotsPerCol))); }
int dot_j(const Viewport& v, double y) {
  return static_cast<int>(std::floor((v.height_u - y) / (v.units_per_row() / kDotsPerRow)));
}

// The lit dots of the field as (i, j).
std::set<std::pair<int, int>> field_dots(const Screen& s, const Viewport& v) {
  std::set<std::pair<int, int>> out;
  for (int j = 0; j < v.rows * kDotsPerRow; ++j)
    for (int i = 0; i < v.cols * kDotsPerCol; ++i)
      if (lit(s, v, i, j)) out.emplace(i, j);
  return out;
}

}  // namespace

TEST_CASE("Fine field: two balls 1 unit apart are drawn apart at 80x24", "[client][fine]") {
  const TerminalSize size{80, 24};
  const ViewState view = fine_view();
  for (const bool across : {true, false}) {
    INFO((across ? "side by side" : "one above the other"));
    Snapshot s = fts::client::test::seed_snapshot(Phase::play);
    // Two enemies of radius 16 whose edges are 1 u apart (issue 37's `#50#48`).
    const BallState a = fine_ball(10, 200, 150, BallKind::enemy, 0, 16, 50);
    BallState b = fine_ball(11, across ? 233 : 200, across ? 150 : 117, BallKind::enemy, 0, 16, 48);
    s.balls = {a, b};
    const Viewport v = arena_viewport(size, view, s);
    const Screen screen = render(s, s, 0, size, view);
    // Along the line through both centres: the first ball's dots, then at least one empty
    // dot, then the second ball's.
    int state = 0;  // 0: in a, 1: in the gap, 2: in b
    const int steps = 400;
    for (int k = 0; k <= steps; ++k) {
      const double t = static_cast<double>(k) / steps;
      const double x = a.x + (b.x - a.x) * t, y = a.y + (b.y - a.y) * t;
      const bool on = lit(screen, v, dot_i(v, x), dot_j(v, y));
      if (state == 0 && !on) state = 1;
      else if (state == 1 && on) state = 2;
    }
    CHECK(state == 2);
    // Both keep their mass labels apart where they fit, and every ball dot is red.
    for (int row = v.row0; row < v.row0 + v.rows; ++row)
      for (int col = v.col0; col < v.col0 + v.cols; ++col)
        if (screen.at(col, row).braille() && screen.at(col, row).dots != 0) CHECK(screen.at(col, row).style.fg == Color::red);
  }
  // The same two in ASCII run together: the reason for the dots.
  Snapshot s = fts::client::test::seed_snapshot(Phase::play);
  s.balls = {fine_ball(10, 200, 150, BallKind::enemy, 0, 16, 50), fine_ball(11, 233, 150, BallKind::enemy, 0, 16, 48)};
  ViewState ascii = fine_view();
  ascii.fine = false;
  const Viewport v = arena_viewport(size, ascii, s);
  const std::string row = render(s, s, 0, size, ascii).line(v.row_of(150));
  CHECK(row.find("##") != std::string::npos);
}

TEST_CASE("Fine field: a ball keeps its round shape and its mass label", "[client][fine]") {
  for (const TerminalSize size : {TerminalSize{80, 24}, TerminalSize{120, 40}}) {
    INFO(size.cols << "x" << size.rows);
    const ViewState view = fine_view();
    Snapshot s = fts::client::test::seed_snapshot(Phase::play);
    s.balls = {fine_ball(1, 250, 150, BallKind::player, 1, 24, 99)};
    const Viewport v = arena_viewport(size, view, s);
    const Screen screen = render(s, s, 0, size, view);
    const auto dots = field_dots(screen, v);
    // As many dots as the disc's area holds (within 15 %), as wide as tall in units.
    const double dot_area = v.units_per_col() / kDotsPerCol * v.units_per_row() / kDotsPerRow;
    const double want = 3.14159265 * 24 * 24 / dot_area;
    CHECK(std::abs(static_cast<double>(dots.size()) - want) <= 0.15 * want);
    int i0 = 1 << 20, i1 = -1, j0 = 1 << 20, j1 = -1;
    for (const auto& [i, j] : dots) i0 = std::min(i0, i), i1 = std::max(i1, i), j0 = std::min(j0, j), j1 = std::max(j1, j);
    const double w = (i1 - i0 + 1) * v.units_per_col() / kDotsPerCol, h = (j1 - j0 + 1) * v.units_per_row() / kDotsPerRow;
    CHECK(std::abs(w - h) <= std::max(v.units_per_col(), v.units_per_row()) / 2);
    // The mass on the ball's middle row, black on the ball's colour; the rest in its colour.
    const std::string mid = screen.line(v.row_of(150));
    CHECK(mid.find("99") != std::string::npos);
    for (int col = v.col0; col < v.col0 + v.cols; ++col) {
      const Cell& c = screen.at(col, v.row_of(150));
      if (c.ch == '9') CHECK(c.style.bg == Color::yellow);
      if (c.braille() && c.dots != 0) CHECK(c.style.fg == Color::yellow);
    }
  }
}

TEST_CASE("Fine field: a moving ball changes its drawing in steps smaller than a cell", "[client][fine]") {
  // The own ball pushed right 0.25 u at a time across one ASCII column: how many times
  // does the drawing change? In dots at least twice as often as in characters.
  const TerminalSize size{80, 24};
  for (const double y : {150.0, 143.0, 131.7}) {
    int changes[2] = {0, 0};
    for (const bool fine : {false, true}) {
      ViewState view = fine_view();
      view.fine = fine;
      Snapshot s = fts::client::test::seed_snapshot(Phase::play);
      const Viewport v = arena_viewport(size, view, s);
      std::vector<std::string> last;
      for (double dx = 0; dx <= v.units_per_col(); dx += 0.25) {
        s.balls = {fine_ball(1, 200.3 + dx, y, BallKind::player, 1, 16)};
        const auto lines = render(s, s, 0, size, view).lines();
        if (!last.empty() && lines != last) ++changes[fine ? 1 : 0];
        last = lines;
      }
    }
    INFO("y " << y << ": ascii " << changes[0] << ", dots " << changes[1]);
    CHECK(changes[1] >= 2 * std::max(changes[0], 1));
  }
}

TEST_CASE("Fine field: dots only where the terminal shows them", "[client][fine]") {
  CHECK(braille_wanted(nullptr, nullptr, "en_US.UTF-8", "xterm-256color"));
  CHECK(braille_wanted("C.utf8", nullptr, "C", "screen"));
  CHECK(braille_wanted(nullptr, "de_DE.UTF-8", nullptr, "tmux-256color"));
  CHECK_FALSE(braille_wanted("C", nullptr, "en_US.UTF-8", "xterm"));  // LC_ALL decides
  CHECK_FALSE(braille_wanted(nullptr, nullptr, nullptr, "xterm"));     // POSIX locale
  CHECK_FALSE(braille_wanted(nullptr, nullptr, "en_US.UTF-8", "linux"));
  CHECK_FALSE(braille_wanted(nullptr, nullptr, "en_US.UTF-8", "dumb"));
  CHECK_FALSE(braille_wanted(nullptr, nullptr, "en_US.UTF-8", "vt100"));
  CHECK_FALSE(braille_wanted(nullptr, nullptr, "en_US.UTF-8", nullptr));
  // Without colour the dots would not tell an enemy from a player: ASCII.
  ViewState view = fine_view();
  view.color = false;
  Snapshot s = fts::client::test::seed_snapshot(Phase::play);
  s.balls = {fine_ball(1, 250, 150, BallKind::player, 1, 16), fine_ball(2, 100, 100, BallKind::enemy, 0, 16)};
  std::string text;
  for (const auto& l : render(s, s, 0, {80, 24}, view).lines()) text += l;
  CHECK(text.find('@') != std::string::npos);
  CHECK(text.find('#') != std::string::npos);
  // With colour, the frame's bytes carry the dots as UTF-8 (U+2800..U+28FF).
  view.color = true;
  const std::string bytes = to_ansi(render(s, s, 0, {80, 24}, view), true);
  CHECK(bytes.find("\xE2\xA3\xBF") != std::string::npos);  // a full cell inside a ball
}

TEST_CASE("a frame rewrites only the rows that changed", "[client][fine]") {
  ViewState view = fine_view();
  Snapshot s = fts::client::test::seed_snapshot(Phase::play);
  s.balls = {fine_ball(1, 250, 150, BallKind::player, 1, 16)};
  std::vector<std::string> last;
  const Screen first = render(s, s, 0, {80, 24}, view);
  const std::string all = repaint(first, last, true);
  CHECK(all.size() >= to_ansi(first, true).size() - 8);  // every row the first time
  CHECK(repaint(first, last, true).empty());             // nothing changed: no bytes
  s.balls[0].x += 1.5;                                   // a few dots over
  const std::string moved = repaint(render(s, s, 0, {80, 24}, view), last, true);
  CHECK_FALSE(moved.empty());
  CHECK(moved.size() * 4 < all.size());  // the ball's rows only
  CHECK(moved.find("\x1b[1;1H") == std::string::npos);  // not the HUD's row
}

TEST_CASE("Fine field: balls on the edges, past them and odd sizes stay on the field", "[client][fine]") {
  // Read beyond the dots of the frame once (the e2e run's heap overflow, under ASan).
  const ViewState view = fine_view();
  for (const TerminalSize size : {TerminalSize{80, 24}, TerminalSize{120, 40}, TerminalSize{60, 20}}) {
    Snapshot s = fts::client::test::seed_snapshot(Phase::play);
    std::uint32_t id = 1;
    for (const double x : {-40.0, 0.0, 0.01, 250.0, 499.99, 500.0, 540.0})
      for (const double y : {-40.0, 0.0, 0.01, 150.0, 299.99, 300.0, 340.0})
      {
        ++id;
        s.balls.push_back(fine_ball(id, x, y, id % 2 == 0 ? BallKind::enemy : BallKind::player, 1 + id % 3, 1 + id % 30));
      }
    s.balls.push_back(fine_ball(id++, 250, 150, BallKind::enemy, 0, 1e9));
    s.balls.push_back(fine_ball(id++, 250, 150, BallKind::rocket, 1, 0));
    const Screen screen = render(s, s, 0, size, view);
    const Viewport v = arena_viewport(size, view, s);
    // Dots only on the platform and its frame.
    for (int row = 0; row < screen.rows(); ++row)
      for (int col = 0; col < screen.cols(); ++col)
        if (screen.at(col, row).braille())
          CHECK((col >= v.col0 - 1 && col <= v.col0 + v.cols && row >= v.row0 - 1 && row <= v.row0 + v.rows));
  }
}
