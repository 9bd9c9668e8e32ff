#include "ui/render.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "ui/hud.hpp"
#include "ui/interpolate.hpp"
#include "ui/palette.hpp"
#include "ui/panel.hpp"
#include "ui/sanitize.hpp"

namespace fts::client {

using protocol::BallKind;
using protocol::BallState;
using protocol::Phase;

namespace {

constexpr Style kHudStyle{Color::none, Color::none, true, false, false};
constexpr Style kDimStyle{Color::gray, Color::none, false, false, false};
constexpr Style kStatusStyle{Color::red, Color::none, true, false, false};
constexpr Style kMessageStyle{Color::cyan, Color::none, false, false, false};
constexpr Style kTitleStyle{Color::yellow, Color::none, true, false, false};

struct BallLook {
  char fill;
  Style style;
  int layer;  // drawn in increasing order: yours last, on top
};

BallLook look_of(const BallState& b, std::uint32_t me) {
  switch (b.kind) {
    case BallKind::enemy: return {kEnemyBallChar, {Color::red, Color::none, true, false, false}, 0};
    case BallKind::rocket: return {kRocketChar, player_style(b.owner), 2};
    case BallKind::player:
      if (b.owner == me) return {kMyBallChar, player_style(b.owner), 3};
      return {kPlayerBallChar, player_style(b.owner), 1};
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

// Cells a ball may cover: the platform and its frame, nothing of the text around it.
bool drawable(const Screen& s, const Viewport& v, int col, int row) {
  return s.inside(col, row) && col >= v.col0 - 1 && col <= v.col0 + v.cols && row >= v.row0 - 1 &&
         row <= v.row0 + v.rows;
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
      if (dx * dx + dy * dy <= r * r && drawable(s, v, col, row)) s.set(col, row, look.fill, look.style);
    }
  }
  if (drawable(s, v, cc, rc)) s.set(cc, rc, look.fill, look.style);  // even a tiny ball shows
  if (b.kind == BallKind::rocket) return;
  // The mass, centred in the ball as in the seed's pictures.
  const std::string label =
      std::isfinite(b.mass) ? std::to_string(std::llround(std::clamp(b.mass, 0.0, 1e9))) : "?";
  const int start = cc - (static_cast<int>(label.size()) - 1) / 2;
  Style label_style = look.style;
  label_style.fg = Color::white;
  for (std::size_t i = 0; i < label.size(); ++i) {
    const int col = start + static_cast<int>(i);
    if (drawable(s, v, col, rc)) s.set(col, rc, label[i], label_style);
  }
}

// A player's name just above its ball (below when the ball is at the top edge), centred
// and truncated; the player being watched gets brackets.
void draw_name(Screen& s, const Viewport& v, const BallState& b, const Snapshot& snap, const ViewState& view) {
  if (!std::isfinite(b.x) || !std::isfinite(b.y) || !std::isfinite(b.radius)) return;
  const PlayerState* p = find_player(snap, b.owner);
  if (p == nullptr) return;
  std::string label = sanitize(p->name, kNameOnFieldChars);
  if (b.owner == view.follow_id) label = "[" + label + "]";
  const double r = std::clamp(b.radius, 0.0, 1e6);
  const int cc = v.col_of(b.x);
  int row = v.row_of(b.y + r) - 1;
  if (row < v.row0 - 1) row = v.row_of(b.y - r) + 1;
  int col = cc - static_cast<int>(label.size()) / 2;
  col = std::clamp(col, v.col0 - 1, v.col0 + v.cols + 1 - static_cast<int>(label.size()));
  Style st = player_style(b.owner);
  if (b.owner == view.follow_id) st.underline = true;
  for (std::size_t i = 0; i < label.size(); ++i)
    if (drawable(s, v, col + static_cast<int>(i), row)) s.set(col + static_cast<int>(i), row, label[i], st);
}

void draw_arena(Screen& s, const Snapshot& snap, const Viewport& v, const ViewState& view) {
  draw_frame(s, v);
  std::vector<std::pair<BallLook, const BallState*>> order;
  for (const auto& b : snap.balls) order.emplace_back(look_of(b, view.my_player_id), &b);
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& x, const auto& y) { return x.first.layer < y.first.layer; });
  for (const auto& [look, ball] : order) draw_ball(s, v, *ball, look);
  for (const auto& [look, ball] : order)
    if (ball->kind == BallKind::player) draw_name(s, v, *ball, snap, view);
}

void put_line(Screen& s, int col, int row, const StyledLine& line, int max_cols) {
  const int end = col + max_cols;
  for (const auto& span : line) {
    for (char ch : span.text) {
      if (col >= end) return;
      s.set(col++, row, ch, span.style);
    }
  }
}

void put_centred(Screen& s, int row, const std::string& text, Style style) {
  const int col = std::max(0, (s.cols() - static_cast<int>(text.size())) / 2);
  s.put(col, row, text, style);
}

// Centred over the platform, cut to its width.
void put_centred(Screen& s, int row, const std::string& text, Style style, const Viewport& v) {
  const std::string cut = text.substr(0, static_cast<std::size_t>(std::max(v.cols, 0)));
  const int col = v.col0 + std::max(0, (v.cols - static_cast<int>(cut.size())) / 2);
  s.put(col, row, cut, style);
}

bool is_group_start(const std::string& line) {
  return line.rfind("Level ", 0) == 0 || line.rfind("Current ", 0) == 0 ||
         line.rfind("Bank Purchased", 0) == 0 || line.rfind("Press Enter", 0) == 0;
}

void draw_shop(Screen& s, const Snapshot& snap, const ViewState& view, const FrameLayout& L) {
  const PlayerState* me = find_player(snap, view.my_player_id);
  const int first = L.area_row0;
  const int last = L.area_row0 + L.area_rows - 3;  // leave the result and ready lines
  const int width = std::max(L.area_cols - 3, 10);
  const std::vector<std::string> board = scoreboard_lines(snap, view, false);
  if (me == nullptr || (me->lives <= 0 && !me->alive)) {
    s.put(2, first, "Level " + std::to_string(snap.level) + " Complete", kTitleStyle);
    s.put(2, first + 2, me == nullptr ? "You are watching: the players are shopping."
                                      : "You are out: watching the others shop.");
    for (std::size_t i = 0; i < board.size() && first + 4 + static_cast<int>(i) <= last; ++i)
      s.put(2, first + 4 + static_cast<int>(i), board[i].substr(0, static_cast<std::size_t>(width)),
            i == 0 ? kTitleStyle : Style{});
  } else {
    std::vector<std::string> raw = shop_screen_lines(*me, snap.level, view.shop_terms);
    std::vector<std::string> lines;
    for (const auto& l : raw)
      for (auto& part : wrap(l, width)) lines.push_back(std::move(part));
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
    // The standings after the level: beside the offers when the terminal is wide enough,
    // else under them when they fit.
    std::size_t text_w = 0;
    for (const auto& line : spaced) text_w = std::max(text_w, line.size());
    const int beside = L.area_col0 + 2 + static_cast<int>(text_w) + 4;
    const int board_w = static_cast<int>(board[1].size());
    if (beside + board_w <= L.area_col0 + L.area_cols) {
      for (std::size_t i = 0; i < board.size() && first + static_cast<int>(i) <= last; ++i)
        s.put(beside, first + static_cast<int>(i), board[i], i == 0 ? kTitleStyle : Style{});
    } else if (last - row >= static_cast<int>(board.size())) {
      for (std::size_t i = 0; i < board.size(); ++i)
        s.put(2, ++row, board[i].substr(0, static_cast<std::size_t>(width)), i == 0 ? kTitleStyle : Style{});
    }
  }
  const int cut = std::max(L.area_cols - 2, 1);
  if (!view.shop_result.empty()) s.put(2, last + 1, view.shop_result.substr(0, static_cast<std::size_t>(cut)), kMessageStyle);
  std::string ready;
  if (const int left = countdown_s(snap, view.tick_rate_hz); left >= 0)
    ready = "Next level in " + std::to_string(left) + " s.   ";
  if (me != nullptr && me->ready) {
    ready += "You are ready: waiting for the others.";
  } else {
    std::string line = ready_line(snap);
    if (static_cast<int>(ready.size() + line.size()) > cut) {
      // Too long for the width: how many are ready, and who is still shopping.
      int total = 0, done = 0;
      std::string waiting;
      for (const auto& p : snap.players) {
        if (p.lives <= 0 && !p.alive) continue;
        ++total;
        if (p.ready) ++done;
        else waiting += (waiting.empty() ? "" : ", ") + sanitize(p.name, 16);
      }
      line = "Ready: " + std::to_string(done) + " of " + std::to_string(total) + "; shopping: " + waiting;
    }
    ready += line;
  }
  s.put(2, last + 2, ready.substr(0, static_cast<std::size_t>(cut)));
}

void draw_standings(Screen& s, const Snapshot& snap, const ViewState& view, const Viewport& v) {
  const std::vector<std::string> board = scoreboard_lines(snap, view, true);
  const int top = std::max(v.row0, v.row0 + v.rows / 2 - static_cast<int>(board.size()) / 2 - 2);
  int row = top;
  const int width = static_cast<int>(board[1].size());
  const int col = std::max(v.col0, v.col0 + (v.cols - width) / 2);
  for (std::size_t i = 0; i < board.size(); ++i) {
    std::string line = board[i];
    line.resize(static_cast<std::size_t>(std::min(width, v.cols)), ' ');
    s.put(col, row++, line, i == 0 ? kTitleStyle : kHudStyle);
  }
  s.put(col, row + 1, std::string(" Press Enter to play again, q to quit ").substr(0, static_cast<std::size_t>(v.cols)), kHudStyle);
}

}  // namespace

Viewport arena_viewport(TerminalSize size, const ViewState& view, const protocol::Snapshot& snap) {
  return frame_layout(size, view, snap).arena;
}

Screen render(const protocol::Snapshot& a, const protocol::Snapshot& b, double alpha,
              TerminalSize size, const ViewState& view) {
  Screen s(size);
  const Snapshot snap = interpolate(a, b, alpha);
  const FrameLayout L = frame_layout({s.cols(), s.rows()}, view, snap);
  if (L.too_small) {
    const auto lines = wrap(too_small_text(size), s.cols());
    int row = std::max(0, (s.rows() - static_cast<int>(lines.size())) / 2);
    for (const auto& line : lines) put_centred(s, row++, line, kStatusStyle);
    return s;
  }
  s.put(0, L.hud_row, hud_fit(snap, view, s.cols()), kHudStyle);
  if (!view.status.empty()) {
    const int col = std::max(0, s.cols() - static_cast<int>(view.status.size()) - 1);
    s.put(col, L.hud_row, " " + view.status, kStatusStyle);
  }
  if (L.side) {
    s.put(L.panel_col0, L.legend_row0, "Players", kHudStyle);
    int row = L.legend_row0 + 1;
    for (const auto& line : legend_lines(snap, view, L.panel_cols, true, L.legend_rows - 1))
      put_line(s, L.panel_col0, row++, line, L.panel_cols);
    s.put(L.panel_col0, L.log_row0, "Messages", kHudStyle);
    const auto log = log_lines(view, L.log_cols, L.log_rows - 1);
    row = L.log_row0 + 1;
    for (const auto& line : log) put_line(s, L.log_col0, row++, line, L.log_cols);
  } else {
    int row = L.legend_row0;
    for (const auto& line : legend_lines(snap, view, s.cols(), false, L.legend_rows))
      put_line(s, 0, row++, line, s.cols());
    const auto log = log_lines(view, L.log_cols, L.log_rows);
    row = L.log_row0 + L.log_rows - static_cast<int>(log.size());
    for (const auto& line : log) put_line(s, L.log_col0, row++, line, L.log_cols);
  }

  if (snap.phase == Phase::shop) {
    draw_shop(s, snap, view, L);
  } else {
    const Viewport& v = L.arena;
    draw_arena(s, snap, v, view);
    const int mid = v.row0 + v.rows / 2;
    const PlayerState* me = find_player(snap, view.my_player_id);
    if (snap.phase == Phase::over) {
      put_centred(s, v.row0, " GAME OVER at level " + std::to_string(snap.level) + " ", kTitleStyle, v);
      draw_standings(s, snap, view, v);
    } else if (snap.phase == Phase::lobby) {
      put_centred(s, mid, " Waiting for the match: press Enter when ready ", kTitleStyle, v);
      if (!snap.players.empty()) put_centred(s, mid + 2, " " + ready_line(snap) + " ", kHudStyle, v);
      if (const int left = countdown_s(snap, view.tick_rate_hz); left >= 0)
        put_centred(s, mid + 4, " The match starts in " + std::to_string(left) + " s, ready or not ", kHudStyle, v);
    } else if (me != nullptr && !me->alive) {
      put_centred(s, mid, me->lives > 0 ? " You fell off: respawning... " : " You are out: watching (Tab: next player) ",
                  kTitleStyle, v);
    }
  }
  s.put(0, L.footer_row, footer_text(snap, view, s.cols()), view.chat_open ? kHudStyle : kDimStyle);
  return s;
}

}  // namespace fts::client
