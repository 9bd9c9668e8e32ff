#include "ui/render.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "net/interpolate.hpp"
#include "ui/board.hpp"
#include "ui/field_cells.hpp"
#include "ui/fine_field.hpp"
#include "ui/hud.hpp"
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
constexpr Style kMineStyle{Color::green, Color::none, true, false, false};

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

void draw_frame(Screen& s, const Viewport& v, bool fine) {
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
    for (int c = v.col0; c < right; ++c) s.set(c, r, fine ? ' ' : kPlatformChar, kDimStyle);
}

// A ball covers the cells of the platform and its frame whose centres lie in its disc
// (at least its centre cell) and records them in `cells` as ball `index`. Its mass is
// written on its middle row when the digits fit on its own cells and leave at least one
// fill cell showing: even a ball two cells wide keeps its '@'.
void draw_ball(Screen& s, const Viewport& v, FieldCells& cells, int index, const BallState& b, const BallLook& look) {
  if (!std::isfinite(b.x) || !std::isfinite(b.y) || !std::isfinite(b.radius)) return;
  const double r = std::clamp(b.radius, 0.0, 1e6);
  const int c0 = v.col_of(b.x - r), c1 = v.col_of(b.x + r);
  const int r0 = v.row_of(b.y + r), r1 = v.row_of(b.y - r);
  const int cc = v.col_of(b.x), rc = v.row_of(b.y);
  const auto paint = [&](int col, int row) {
    if (!cells.on_field(col, row) || !s.inside(col, row)) return;
    s.set(col, row, look.fill, look.style);
    cells.cover(col, row, index);
  };
  for (int row = std::max(r0, v.row0 - 1); row <= std::min(r1, v.row0 + v.rows); ++row) {
    for (int col = std::max(c0, v.col0 - 1); col <= std::min(c1, v.col0 + v.cols); ++col) {
      const double dx = v.x_of(col) - b.x, dy = v.y_of(row) - b.y;
      if (dx * dx + dy * dy <= r * r) paint(col, row);
    }
  }
  paint(cc, rc);  // even a tiny ball shows
  if (b.kind == BallKind::rocket) return;
  // The mass, centred in the ball as in the seed's pictures.
  const std::string label =
      std::isfinite(b.mass) ? std::to_string(std::llround(std::clamp(b.mass, 0.0, 1e9))) : "?";
  const int n = static_cast<int>(label.size());
  const int start = cc - (n - 1) / 2;
  if (cells.cells_of(index) <= n) return;
  for (int i = 0; i < n; ++i)
    if (cells.ball_at(start + i, rc) != index) return;
  Style label_style = look.style;
  label_style.fg = Color::white;
  for (int i = 0; i < n; ++i) s.set(start + i, rc, label[static_cast<std::size_t>(i)], label_style);
}

// A player's name (cut, in brackets when watched) next to its ball: the first free spot
// above, below, right or left of it; first one that touches no other ball, then any; a
// name with no free spot is shortened (to 6, then 3 characters), else left out.
void draw_name(Screen& s, FieldCells& cells, int index, const BallState& b, const Snapshot& snap,
               const ViewState& view) {
  const PlayerState* p = find_player(snap, b.owner);
  if (p == nullptr) return;
  const std::string name = sanitize(p->name, kNameOnFieldChars);
  const bool watched = b.owner == view.follow_id;
  Style st = player_style(b.owner);
  if (watched) st.underline = true;
  std::vector<std::size_t> keeps{name.size()};
  for (const std::size_t shorter : {std::size_t{6}, std::size_t{3}})
    if (name.size() > shorter) keeps.push_back(shorter);
  for (const std::size_t keep : keeps) {
    const std::string cut = name.substr(0, keep);
    const std::string label = watched ? "[" + cut + "]" : cut;
    const int n = static_cast<int>(label.size());
    for (const bool strict : {true, false}) {
      if (const auto spot = cells.find_spot(index, n, strict)) {
        s.put(spot->col, spot->row, label, st);
        cells.take(*spot, n);
        return;
      }
    }
  }
}

void draw_arena(Screen& s, const Snapshot& snap, const Viewport& v, const ViewState& view) {
  const bool fine = view.fine && view.color;  // dots need colour to tell the balls apart
  draw_frame(s, v, fine);
  std::vector<std::pair<BallLook, const BallState*>> order;
  for (const auto& b : snap.balls) order.emplace_back(look_of(b, view.my_player_id), &b);
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& x, const auto& y) { return x.first.layer < y.first.layer; });
  FieldCells cells(v);
  if (fine) {
    std::vector<FineBall> balls;
    for (const auto& [look, b] : order) balls.push_back({b, look.style, b->kind != BallKind::rocket});
    draw_balls_fine(s, v, cells, balls);
  } else {
    for (std::size_t i = 0; i < order.size(); ++i) draw_ball(s, v, cells, static_cast<int>(i), *order[i].second, order[i].first);
  }
  // The own ball's exhaust: one cell behind it against its thrust, drawn the frame the key
  // is pressed (the ball's first cell of motion takes the physics up to ~0.3 s from rest;
  // the exhaust shows at once that it is thrusting).
  if (view.thrust_x != 0 || view.thrust_y != 0) {
    for (std::size_t i = 0; i < order.size(); ++i) {
      const BallState& b = *order[i].second;
      if (b.kind != BallKind::player || b.owner != view.my_player_id) continue;
      const double reach = b.radius + 0.5 * std::max(v.units_per_col(), v.units_per_row());
      const double len = (view.thrust_x != 0 && view.thrust_y != 0) ? 0.7071 : 1.0;
      const int col = v.col_of(b.x - view.thrust_x * reach * len), row = v.row_of(b.y - view.thrust_y * reach * len);
      if (cells.on_platform(col, row) && cells.ball_at(col, row) < 0) {
        const char ch = view.thrust_y == 0 ? kExhaustSide : view.thrust_x == 0 ? kExhaustUpDown : kExhaustDiagonal;
        s.set(col, row, ch, player_style(b.owner));
        cells.cover(col, row, static_cast<int>(i));
      }
    }
  }
  // Names after every ball, so that none is covered: yours first, then the watched
  // player's, then the others by ball id.
  std::vector<int> named;
  for (std::size_t i = 0; i < order.size(); ++i)
    if (order[i].second->kind == BallKind::player) named.push_back(static_cast<int>(i));
  const auto rank = [&](int i) {
    const std::uint32_t owner = order[static_cast<std::size_t>(i)].second->owner;
    return owner == view.my_player_id ? 0 : owner == view.follow_id ? 1 : 2;
  };
  std::stable_sort(named.begin(), named.end(), [&](int x, int y) {
    if (rank(x) != rank(y)) return rank(x) < rank(y);
    return order[static_cast<std::size_t>(x)].second->id < order[static_cast<std::size_t>(y)].second->id;
  });
  for (const int i : named) draw_name(s, cells, i, *order[static_cast<std::size_t>(i)].second, snap, view);
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

void draw_shop(Screen& s, const Snapshot& snap, const ViewState& view, const FrameLayout& L) {
  const PlayerState* me = find_player(snap, view.my_player_id);
  const int first = L.area_row0;
  const int last = L.area_row0 + L.area_rows - 3;  // leave the result and ready lines
  const int width = std::max(L.area_cols - 3, 10);
  const std::vector<std::string> board = scoreboard_lines(snap, view, false);
  // The player's best (ui/board.hpp): beside the slide's title, else on the result line.
  const std::string best = best_line(view, snap.level);
  bool best_shown = best.empty();
  if (me == nullptr || (me->lives <= 0 && !me->alive)) {
    best_shown = true;
    s.put(2, first, "Level " + std::to_string(snap.level) + " Complete", kTitleStyle);
    if (me != nullptr && !best.empty()) s.put(2, first + 1, best.substr(0, static_cast<std::size_t>(width)), kMineStyle);
    s.put(2, first + 2, me == nullptr ? "You are watching: the players are shopping."
                                      : "You are out: watching the others shop.");
    for (std::size_t i = 0; i < board.size() && first + 4 + static_cast<int>(i) <= last; ++i)
      s.put(2, first + 4 + static_cast<int>(i), board[i].substr(0, static_cast<std::size_t>(width)),
            i == 0 ? kTitleStyle : Style{});
  } else {
    const std::vector<std::vector<std::string>> variants = shop_variants(*me, snap.level, view.shop_terms, width);
    const int room = last - first + 1;
    const int board_w = static_cast<int>(board[1].size());
    const auto text_w = [](const std::vector<std::string>& v) {
      std::size_t w = 0;
      for (const auto& line : v) w = std::max(w, line.size());
      return static_cast<int>(w);
    };
    const auto beside_col = [&](const std::vector<std::string>& v) { return L.area_col0 + 2 + text_w(v) + 4; };
    const auto fits_beside = [&](const std::vector<std::string>& v) {
      return beside_col(v) + board_w <= L.area_col0 + L.area_cols;
    };
    const auto fits_under = [&](const std::vector<std::string>& v) {
      return std::ssize(v) + 1 + std::ssize(board) <= room;
    };
    // The most spacious slide that fits, and the standings beside or under it when some
    // slide leaves room for them: under it at the cost of blank lines and repeated lines,
    // never of the explanations.
    std::size_t pick = variants.size() - 1;
    for (std::size_t i = variants.size(); i-- > 0;)
      if (std::ssize(variants[i]) <= room) pick = i;
    bool with_board = false;
    for (std::size_t i = 0; i < variants.size() && !with_board; ++i) {
      const bool under = i + 1 < variants.size() && fits_under(variants[i]);
      if (std::ssize(variants[i]) <= room && (fits_beside(variants[i]) || under)) {
        pick = i;
        with_board = true;
      }
    }
    const std::vector<std::string>& spaced = variants[pick];
    int row = first;
    for (const auto& line : spaced) {
      if (row > last) break;
      Style style;
      const bool title = line.rfind("Level ", 0) == 0 && line.find("Complete") != std::string::npos;
      if (title) style = kTitleStyle;
      else if (line.rfind("To ", 0) == 0 || line.rfind("Press ", 0) == 0) style.bold = true;
      s.put(2, row, line, style);
      if (title && !best_shown && line.size() + 4 + best.size() <= static_cast<std::size_t>(std::max(text_w(spaced), 0))) {
        s.put(2 + static_cast<int>(line.size()) + 4, row, best, kMineStyle);
        best_shown = true;
      }
      ++row;
    }
    // The standings after the level: beside the offers when the terminal is wide enough,
    // else under them.
    if (with_board && fits_beside(spaced)) {
      const int beside = beside_col(spaced);
      for (std::size_t i = 0; i < board.size() && first + static_cast<int>(i) <= last; ++i)
        s.put(beside, first + static_cast<int>(i), board[i], i == 0 ? kTitleStyle : Style{});
    } else if (with_board) {
      for (std::size_t i = 0; i < board.size(); ++i)
        s.put(2, ++row, board[i].substr(0, static_cast<std::size_t>(width)), i == 0 ? kTitleStyle : Style{});
    }
  }
  const int cut = std::max(L.area_cols - 2, 1);
  if (!view.shop_result.empty() && view.now_ms < view.shop_result_ms + kShopResultShowMs) s.put(2, last + 1, view.shop_result.substr(0, static_cast<std::size_t>(cut)), kMessageStyle);
  else if (!best_shown) s.put(2, last + 1, best.substr(0, static_cast<std::size_t>(cut)), kMineStyle);
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
  // Your place on the server's board, with this match counted (asked for at game over).
  const std::string own = view.board ? own_board_line(view) : std::string();
  if (!own.empty() && row + 3 < v.row0 + v.rows)
    put_centred(s, row + 3, " " + own + " ", view.board->rank != 0 ? kMineStyle : kHudStyle, v);
}

// The waiting screen: what to press, who is ready, the countdown, and the leaderboard
// under them (ui/board.hpp) with the player's own place; without a board, the three lines
// in the middle as before it.
void draw_lobby(Screen& s, const Snapshot& snap, const ViewState& view, const Viewport& v) {
  const int left = countdown_s(snap, view.tick_rate_hz);
  const std::vector<BoardLine> board = board_lines(view, v.cols - 2, v.rows - 5);
  if (board.empty()) {
    const int mid = v.row0 + v.rows / 2;
    put_centred(s, mid, " Waiting for the match: press Enter when ready ", kTitleStyle, v);
    if (!snap.players.empty()) put_centred(s, mid + 2, " " + ready_line(snap) + " ", kHudStyle, v);
    if (left >= 0) put_centred(s, mid + 4, " The match starts in " + std::to_string(left) + " s, ready or not ", kHudStyle, v);
    return;
  }
  // The board's lines share one left edge and a cleared box, centred on the platform.
  int width = 0;
  for (const auto& l : board) width = std::max(width, static_cast<int>(l.text.size()));
  width = std::min(width + 2, v.cols);
  const int used = 4 + static_cast<int>(board.size());
  int row = v.row0 + std::max(0, (v.rows - used) / 2);
  put_centred(s, row, " Waiting for the match: press Enter when ready ", kTitleStyle, v);
  if (!snap.players.empty()) put_centred(s, row + 1, " " + ready_line(snap) + " ", kHudStyle, v);
  if (left >= 0) put_centred(s, row + 2, " The match starts in " + std::to_string(left) + " s, ready or not ", kHudStyle, v);
  row += 4;
  const int col = v.col0 + std::max(0, (v.cols - width) / 2);
  for (const auto& l : board) {
    std::string text = " " + l.text;
    text.resize(static_cast<std::size_t>(width), ' ');
    const Style style = l.title ? kTitleStyle : l.mine ? kMineStyle : kHudStyle;
    s.put(col, row++, text, style);
  }
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
  // A status ("connection lost, ...") takes the right end: the HUD shortens to leave it.
  const int status_cols = view.status.empty() ? 0 : static_cast<int>(view.status.size()) + 2;
  s.put(0, L.hud_row, hud_fit(snap, view, std::max(s.cols() - status_cols, 0)), kHudStyle);
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
      draw_lobby(s, snap, view, v);
    } else if (me != nullptr && !me->alive) {
      put_centred(s, mid, me->lives > 0 ? " You fell off: respawning... " : " You are out: watching (Tab: next player) ",
                  kTitleStyle, v);
    }
  }
  s.put(0, L.footer_row, footer_text(snap, view, s.cols()), view.chat_open ? kHudStyle : kDimStyle);
  return s;
}

}  // namespace fts::client
