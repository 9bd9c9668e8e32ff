#include "ui/render.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "ui/hud.hpp"
#include "ui/interpolate.hpp"

namespace fts::client {

using protocol::BallKind;
using protocol::BallState;
using protocol::Phase;

namespace {

constexpr Style kHudStyle{Color::none, Color::none, true, false};
constexpr Style kDimStyle{Color::gray, Color::none, false, false};
constexpr Style kStatusStyle{Color::red, Color::none, true, false};
constexpr Style kMessageStyle{Color::cyan, Color::none, false, false};
constexpr Style kTitleStyle{Color::yellow, Color::none, true, false};

struct BallLook {
  char fill;
  Style style;
  int layer;  // drawn in increasing order: yours last, on top
};

BallLook look_of(const BallState& b, std::uint32_t me) {
  switch (b.kind) {
    case BallKind::enemy: return {kEnemyBallChar, {Color::red, Color::none, true, false}, 0};
    case BallKind::rocket: return {kRocketChar, {Color::magenta, Color::none, true, false}, 2};
    case BallKind::player:
      if (b.owner == me) return {kMyBallChar, {Color::yellow, Color::none, true, false}, 3};
      return {kPlayerBallChar, {Color::cyan, Color::none, true, false}, 1};
  }
  return {'?', {}, 0};
}

void draw_frame(Screen& s, const Viewport& v) {
  const int left = v.col0 - 1, right = v.col0 + v.cols, top = v.row0 - 1, bottom = v.row0 + v.rows;
  for (int c = left; c <= right; ++c) {
    const char ch = (c == left || c == right) ? '+' : '-';
    s.set(c, top, ch, kDimStyle);
    s.set(c, bottom, ch, kDimStyle);
  }
  for (int r = v.row0; r < bottom; ++r) {
    s.set(left, r, '|', kDimStyle);
    s.set(right, r, '|', kDimStyle);
  }
  for (int r = v.row0; r < bottom; ++r)
    for (int c = v.col0; c < right; ++c) s.set(c, r, kPlatformChar, kDimStyle);
}

// Cells a ball may cover: the arena area between the text rows, frame included.
bool drawable(const Screen& s, int col, int row) {
  return s.inside(col, row) && row >= kTopRows && row < s.rows() - kBottomRows;
}

void draw_ball(Screen& s, const Viewport& v, const BallState& b, const BallLook& look) {
  if (!std::isfinite(b.x) || !std::isfinite(b.y) || !std::isfinite(b.radius)) return;
  const double r = std::clamp(b.radius, 0.0, 1e6);
  const int c0 = v.col_of(b.x - r), c1 = v.col_of(b.x + r);
  const int r0 = v.row_of(b.y + r), r1 = v.row_of(b.y - r);
  const int cc = v.col_of(b.x), rc = v.row_of(b.y);
  for (int row = std::max(r0, 0); row <= std::min(r1, s.rows()); ++row) {
    for (int col = std::max(c0, 0); col <= std::min(c1, s.cols()); ++col) {
      const double dx = v.x_of(col) - b.x, dy = v.y_of(row) - b.y;
      if (dx * dx + dy * dy <= r * r && drawable(s, col, row)) s.set(col, row, look.fill, look.style);
    }
  }
  if (drawable(s, cc, rc)) s.set(cc, rc, look.fill, look.style);  // even a tiny ball shows
  if (b.kind == BallKind::rocket) return;
  // The mass, centred in the ball as in the seed's pictures.
  const std::string label =
      std::isfinite(b.mass) ? std::to_string(std::llround(std::clamp(b.mass, 0.0, 1e9))) : "?";
  const int start = cc - (static_cast<int>(label.size()) - 1) / 2;
  Style label_style = look.style;
  label_style.fg = Color::white;
  for (std::size_t i = 0; i < label.size(); ++i) {
    const int col = start + static_cast<int>(i);
    if (drawable(s, col, rc)) s.set(col, rc, label[i], label_style);
  }
}

void draw_arena(Screen& s, const Snapshot& snap, const Viewport& v, const ViewState& view) {
  draw_frame(s, v);
  std::vector<std::pair<BallLook, const BallState*>> order;
  for (const auto& b : snap.balls) order.emplace_back(look_of(b, view.my_player_id), &b);
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& x, const auto& y) { return x.first.layer < y.first.layer; });
  for (const auto& [look, ball] : order) draw_ball(s, v, *ball, look);
}

void put_centred(Screen& s, int row, const std::string& text, Style style) {
  const int col = std::max(0, (s.cols() - static_cast<int>(text.size())) / 2);
  s.put(col, row, text, style);
}

bool is_group_start(const std::string& line) {
  return line.rfind("Level ", 0) == 0 || line.rfind("Current ", 0) == 0 ||
         line.rfind("Bank Purchased", 0) == 0 || line.rfind("Press Enter", 0) == 0;
}

void draw_shop(Screen& s, const Snapshot& snap, const ViewState& view) {
  const PlayerState* me = find_player(snap, view.my_player_id);
  const int first = kTopRows;
  const int last = s.rows() - kBottomRows - 3;  // leave the result and ready lines
  if (me == nullptr) {
    s.put(2, first, "Level " + std::to_string(snap.level) + " Complete", kTitleStyle);
    s.put(2, first + 2, "You are watching: the players are shopping.");
  } else {
    std::vector<std::string> lines = shop_screen_lines(*me, snap.level, view.shop_terms);
    const int room = last - first + 1;
    std::vector<std::string> spaced;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (i > 0 && is_group_start(lines[i])) spaced.emplace_back();
      spaced.push_back(lines[i]);
    }
    // Too tall: drop the blank lines, then the Level/Coins/Lives lines the HUD repeats.
    if (static_cast<int>(spaced.size()) > room) spaced = lines;
    if (static_cast<int>(spaced.size()) > room) spaced.erase(spaced.begin(), spaced.begin() + 3);
    if (static_cast<int>(spaced.size()) > room)
      std::erase_if(spaced, [](const std::string& l) { return l.rfind("Increases", 0) == 0 || l.rfind("Earns", 0) == 0; });
    int row = first;
    for (const auto& line : spaced) {
      if (row > last) break;
      Style style;
      if (line.rfind("Level ", 0) == 0 && line.find("Complete") != std::string::npos) style = kTitleStyle;
      else if (line.rfind("To ", 0) == 0 || line.rfind("Press ", 0) == 0) style.bold = true;
      s.put(2, row++, line, style);
    }
  }
  if (!view.shop_result.empty()) s.put(2, last + 1, view.shop_result, kMessageStyle);
  std::string ready = ready_line(snap);
  if (me != nullptr && me->ready) ready += "   You are ready: waiting for the others.";
  if (const int left = countdown_s(snap, view.tick_rate_hz); left >= 0)
    ready += "   Next level in " + std::to_string(left) + " s.";
  s.put(2, last + 2, ready);
}

}  // namespace

Viewport arena_viewport(TerminalSize size, const ViewState& view) {
  // One cell of frame on each side of the platform.
  const int cols = std::max(size.cols - 2, 1);
  const int rows = std::max(size.rows - kTopRows - kBottomRows - 2, 1);
  return fit_arena(1, kTopRows + 1, cols, rows, view.arena_width_u, view.arena_height_u);
}

Screen render(const protocol::Snapshot& a, const protocol::Snapshot& b, double alpha,
              TerminalSize size, const ViewState& view) {
  Screen s(size);
  const Snapshot snap = interpolate(a, b, alpha);
  s.put(0, 0, hud_line(snap, view), kHudStyle);
  s.put(0, 1, players_line(snap, view));
  if (!view.status.empty()) s.put(0, 2, view.status, kStatusStyle);
  else if (!view.messages.empty()) s.put(0, 2, view.messages.back(), kMessageStyle);

  if (snap.phase == Phase::shop) {
    draw_shop(s, snap, view);
  } else {
    const Viewport v = arena_viewport({s.cols(), s.rows()}, view);
    draw_arena(s, snap, v, view);
    const int mid = v.row0 + v.rows / 2;
    const PlayerState* me = find_player(snap, view.my_player_id);
    if (snap.phase == Phase::over) {
      put_centred(s, mid - 1, " GAME OVER at level " + std::to_string(snap.level) + " ", kTitleStyle);
      put_centred(s, mid + 1, " Press Enter to play again, q to quit ", kHudStyle);
    } else if (snap.phase == Phase::lobby) {
      put_centred(s, mid, " Waiting for the match to start: press Enter when ready ", kTitleStyle);
      if (!snap.players.empty()) put_centred(s, mid + 2, " " + ready_line(snap) + " ", kHudStyle);
      if (const int left = countdown_s(snap, view.tick_rate_hz); left >= 0)
        put_centred(s, mid + 4, " The match starts in " + std::to_string(left) + " s, ready or not ", kHudStyle);
    } else if (me != nullptr && !me->alive) {
      put_centred(s, mid, me->lives > 0 ? " You fell off: respawning... " : " You are out: watching ",
                  kTitleStyle);
    }
  }
  s.put(0, s.rows() - 1, help_line(snap.phase), kDimStyle);
  return s;
}

}  // namespace fts::client
