#include "ui/board.hpp"

#include <algorithm>

#include "fts/sim/shop_text.hpp"
#include "ui/sanitize.hpp"

namespace fts::client {

namespace {

std::string cut(std::string s, int cols) {
  if (static_cast<int>(s.size()) > cols) s.resize(static_cast<std::size_t>(std::max(cols, 0)));
  return s;
}

std::string pad_right(std::string s, std::size_t n) {
  if (s.size() < n) s.append(n - s.size(), ' ');
  return s;
}

std::string pad_left(std::string s, std::size_t n) {
  if (s.size() < n) s.insert(0, n - s.size(), ' ');
  return s;
}

std::string count_text(std::int64_t n) { return sim::with_thousands(n); }

}  // namespace

std::string own_board_line(const ViewState& view) {
  if (view.guest) return "You play as a guest: nothing is recorded.";
  if (!view.board) return "";
  const protocol::Leaderboard& b = *view.board;
  if (b.rank == 0) return "You: no match recorded yet. Finish one to get on the board.";
  return "You: #" + count_text(b.rank) + " of " + count_text(b.of) + ", best level " + count_text(b.best) + " (" +
         count_text(b.best_coins) + " coins)";
}

std::vector<BoardLine> board_lines(const ViewState& view, int cols, int rows) {
  std::vector<BoardLine> out;
  if (rows <= 0 || cols <= 0) return out;
  if (!view.board) {
    if (!view.board_note.empty()) out.push_back({cut(view.board_note, cols), false, false});
    return out;
  }
  const protocol::Leaderboard& b = *view.board;
  const std::string own = own_board_line(view);
  if (rows == 1) {
    out.push_back({cut(own, cols), false, true});
    return out;
  }
  out.push_back({cut("Best levels on this server (" + count_text(b.of) + (b.of == 1 ? " player)" : " players)"), cols),
                 true, false});
  const std::size_t shown = std::min<std::size_t>(b.top.size(), static_cast<std::size_t>(std::max(rows - 2, 0)));
  if (b.top.empty() && rows >= 3) out.push_back({cut("No match recorded yet.", cols), false, false});
  std::size_t rank_w = 2;
  for (std::size_t i = 0; i < shown; ++i) rank_w = std::max(rank_w, std::to_string(b.top[i].rank).size());
  std::size_t level_w = 1;
  for (std::size_t i = 0; i < shown; ++i) level_w = std::max(level_w, std::to_string(b.top[i].level).size());
  for (std::size_t i = 0; i < shown; ++i) {
    const protocol::BoardRow& r = b.top[i];
    const std::string name = sanitize(r.name, protocol::kMaxNameBytes);
    const std::string line = pad_left(std::to_string(r.rank), rank_w) + ". " +
                             pad_right(name.empty() ? std::string("?") : name, protocol::kMaxNameBytes) +
                             "  level " + pad_left(std::to_string(r.level), level_w) + "  " +
                             count_text(r.coins) + " coins";
    out.push_back({cut(line, cols), false, b.rank != 0 && r.rank == b.rank});
  }
  if (!own.empty()) out.push_back({cut(own, cols), false, true});
  return out;
}

std::string best_line(const ViewState& view, std::uint32_t level) {
  if (view.guest || !view.board) return "";
  const protocol::Leaderboard& b = *view.board;
  const std::int64_t now = level;
  if (b.rank == 0) return now > 0 ? "Your first match: level " + count_text(now) + " so far" : "";
  if (now > b.best) return "A new best: level " + count_text(now) + " (was " + count_text(b.best) + ")";
  return "Your best: level " + count_text(b.best) + " (#" + count_text(b.rank) + " of " + count_text(b.of) + ")";
}

}  // namespace fts::client
