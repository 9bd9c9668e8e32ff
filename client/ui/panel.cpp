#include "ui/panel.hpp"

#include <algorithm>
#include <cstdio>

#include "fts/sim/shop_text.hpp"
#include "ui/hud.hpp"
#include "ui/palette.hpp"
#include "ui/render.hpp"
#include "ui/sanitize.hpp"

namespace fts::client {

using protocol::Phase;
using protocol::Snapshot;

namespace {

constexpr Style kDim{Color::gray, Color::none, false, false, false};
constexpr int kLegendTopMaxRows = 3;
constexpr int kTopLogRows = 3;
constexpr int kRoomyRows = 30;         // from this many rows the top layout's log keeps 3 rows
constexpr int kSideMinFieldCols = 64;   // the side panel leaves the platform at least this wide
constexpr int kShopMinCols = 58;  // the widest line of the shop's slide, with its margin

std::string fit_name(const std::string& name, int width) {
  const std::string clean = sanitize(name, 16);
  if (width <= 0) return {};
  if (static_cast<int>(clean.size()) <= width) return clean;
  return clean.substr(0, static_cast<std::size_t>(width));
}

char marker_of(const PlayerState& p, const ViewState& view) {
  return p.id == view.my_player_id ? kMyBallChar : kPlayerBallChar;
}

std::string flag_of(const PlayerState& p, Phase phase) {
  if (p.away) return " away";  // its client is gone for now: not playing, whatever its ball does
  if (p.lives <= 0 && !p.alive) return " out";
  if ((phase == Phase::shop || phase == Phase::lobby) && p.ready) return " rdy";
  return "";
}

// " 1,286c 3L out": what follows the name.
std::string stats_of(const PlayerState& p, Phase phase) {
  return " " + sim::with_thousands(p.coins) + "c " + std::to_string(p.lives) + "L" + flag_of(p, phase);
}

Style line_style(const PlayerState& p, const ViewState& view) {
  Style st = player_style(p.id, p.id == view.my_player_id);
  if (p.id == view.follow_id) st.underline = true;
  if (p.away) st.dim = true;
  return st;
}

int total_width(const StyledLine& l) {
  int n = 0;
  for (const auto& s : l) n += static_cast<int>(s.text.size());
  return n;
}

}  // namespace

std::string too_small_text(TerminalSize size) {
  return "terminal too small: " + std::to_string(size.cols) + "x" + std::to_string(size.rows) + ", need at least " +
         std::to_string(kMinCols) + "x" + std::to_string(kMinRows);
}

std::vector<std::string> wrap(const std::string& text, int cols) {
  std::vector<std::string> out;
  if (cols <= 0) return out;
  std::string rest = text;
  while (static_cast<int>(rest.size()) > cols) {
    std::size_t cut = rest.rfind(' ', static_cast<std::size_t>(cols));
    if (cut == std::string::npos || cut == 0) {
      out.push_back(rest.substr(0, static_cast<std::size_t>(cols)));
      rest.erase(0, static_cast<std::size_t>(cols));
    } else {
      out.push_back(rest.substr(0, cut));
      rest.erase(0, cut + 1);
    }
  }
  out.push_back(rest);
  return out;
}

namespace {

bool is_group_start(const std::string& line) {
  return line.rfind("Level ", 0) == 0 || line.rfind("Current ", 0) == 0 ||
         line.rfind("Bank Purchased", 0) == 0 || line.rfind("Press Enter", 0) == 0;
}

}  // namespace

std::vector<std::vector<std::string>> shop_variants(const PlayerState& me, std::uint32_t level,
                                                    const sim::ShopTerms& terms, int width) {
  std::vector<std::string> lines;
  for (const auto& l : shop_screen_lines(me, level, terms))
    for (auto& part : wrap(l, width)) lines.push_back(std::move(part));
  // The slide from the most spacious to the most compact: with blank lines between the
  // groups; without them; without the Level/Coins/Lives lines the HUD repeats; without
  // the items' explanations.
  std::vector<std::vector<std::string>> variants(1);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (i > 0 && is_group_start(lines[i])) variants[0].emplace_back();
    variants[0].push_back(lines[i]);
  }
  variants.push_back(lines);
  variants.push_back(lines);
  variants.back().erase(variants.back().begin(), variants.back().begin() + std::min<std::ptrdiff_t>(3, std::ssize(lines)));
  variants.push_back(variants.back());
  std::erase_if(variants.back(),
                [](const std::string& l) { return l.rfind("Increases", 0) == 0 || l.rfind("Earns", 0) == 0; });
  return variants;
}

int shop_rows_needed(const Snapshot& snap, const ViewState& view, int cols) {
  const std::size_t board = scoreboard_lines(snap, view, false).size();
  const PlayerState* me = find_player(snap, view.my_player_id);
  constexpr int kResultAndReady = 2;
  if (me == nullptr || (me->lives <= 0 && !me->alive)) return 4 + static_cast<int>(board) + kResultAndReady;
  const std::vector<std::string> slide = shop_variants(*me, snap.level, view.shop_terms, std::max(cols - 3, 10)).front();
  std::size_t text_w = 0;
  for (const auto& line : slide) text_w = std::max(text_w, line.size());
  const std::size_t board_w = scoreboard_lines(snap, view, false)[1].size();
  const bool beside = 2 + text_w + 4 + board_w <= static_cast<std::size_t>(cols);
  const std::size_t under = beside ? 0 : 1 + board;
  return static_cast<int>(std::max(slide.size() + under, beside ? board : 0)) + kResultAndReady;
}

std::string hud_fit(const Snapshot& s, const ViewState& view, int cols) {
  std::string full = hud_line(s, view);
  if (static_cast<int>(full.size()) <= cols) return full;
  const PlayerState* me = find_player(s, view.my_player_id);
  std::string mid = "Level " + std::to_string(s.level);
  std::string small = "L" + std::to_string(s.level);
  if (me != nullptr) {
    mid += "  Coins " + sim::with_thousands(me->coins) + "  Lives " + std::to_string(me->lives);
    small += " " + sim::with_thousands(me->coins) + "c " + std::to_string(me->lives) + "L";
    if (const int left = protection_s(*me, s, view.tick_rate_hz); left >= 0) {
      mid += "  Protected " + std::to_string(left) + "s";
      small += " P" + std::to_string(left) + "s";
    }
  }
  char buf[48];
  if (view.ping_ms >= 0) {
    std::snprintf(buf, sizeof buf, "%.0f ms", view.ping_ms);
    mid += std::string("  ") + buf;
    small += std::string(" ") + buf;
  }
  if (view.loss_percent >= 0) {
    std::snprintf(buf, sizeof buf, "%.1f%% loss", view.loss_percent);
    mid += std::string("  ") + buf;
    std::snprintf(buf, sizeof buf, "%.0f%%", view.loss_percent);
    small += std::string(" ") + buf;
  }
  if (view.delay_ms >= 0) mid += "  delay " + std::to_string(view.delay_ms) + " ms";
  // The room code stays to the end (friends join by it): the other parts shorten first.
  const std::string room = view.room.empty() ? "" : "  " + view.room;
  if (static_cast<int>(mid.size() + room.size()) <= cols) return mid + room;
  if (static_cast<int>(small.size() + room.size()) <= cols) return small + room;
  const int left = std::max(cols - static_cast<int>(room.size()), 0);
  if (left > 0) return small.substr(0, static_cast<std::size_t>(left)) + room;
  return view.room.substr(0, static_cast<std::size_t>(std::max(cols, 0)));
}

std::vector<StyledLine> legend_lines(const Snapshot& s, const ViewState& view, int cols, bool one_per_row,
                                     int max_rows) {
  std::vector<StyledLine> out;
  if (cols <= 0 || max_rows <= 0) return out;
  if (one_per_row) {
    for (const auto& p : s.players) {
      if (static_cast<int>(out.size()) >= max_rows) break;
      const std::string stats = stats_of(p, s.phase);
      const int name_w = std::max(cols - 2 - static_cast<int>(stats.size()), 3);
      std::string name = fit_name(p.name, name_w);
      name.resize(static_cast<std::size_t>(name_w), ' ');
      const Style st = line_style(p, view);
      StyledLine line{{std::string(1, marker_of(p, view)) + " ", player_style(p.id)}, {name, st}, {stats, Style{}}};
      while (total_width(line) > cols && !line.back().text.empty()) line.back().text.pop_back();
      out.push_back(std::move(line));
    }
    return out;
  }
  for (const int name_w : {16, 10, 6, 3}) {
    out.clear();
    StyledLine row;
    int used = 0;
    for (const auto& p : s.players) {
      const std::string name = fit_name(p.name, name_w);
      const std::string stats = stats_of(p, s.phase);
      const int w = 2 + static_cast<int>(name.size() + stats.size());
      const int gap = row.empty() ? 0 : 2;
      if (!row.empty() && used + gap + w > cols) {
        out.push_back(std::move(row));
        row.clear();
        used = 0;
      }
      if (!row.empty()) row.push_back({"  ", Style{}});
      row.push_back({std::string(1, marker_of(p, view)) + " ", player_style(p.id)});
      row.push_back({name, line_style(p, view)});
      row.push_back({stats, Style{}});
      used += (row.size() > 3 ? 2 : 0) + w;
    }
    if (!row.empty()) out.push_back(std::move(row));
    if (static_cast<int>(out.size()) <= max_rows) return out;
  }
  out.resize(static_cast<std::size_t>(max_rows));
  return out;
}

std::string age_text(std::uint64_t at_ms, std::uint64_t now_ms) {
  const std::uint64_t s = now_ms > at_ms ? (now_ms - at_ms) / 1000 : 0;
  if (s < 60) return std::to_string(s) + "s";
  if (s < 3600) return std::to_string(s / 60) + "m";
  return std::to_string(std::min<std::uint64_t>(s / 3600, 99)) + "h";
}

std::vector<StyledLine> log_lines(const ViewState& view, int cols, int rows) {
  std::vector<StyledLine> out;
  if (cols <= 4 || rows <= 0) return out;
  // The newest kLogShown lines, except that a host announcement younger than
  // kAnnouncePinnedMs keeps its place: at a level's end the level's own lines would push
  // it out within a second. (Rejected: a HUD row of its own, which costs a row always.)
  const auto pinned = [&](const LogLine& m) { return m.host && view.now_ms < m.at_ms + kAnnouncePinnedMs; };
  const std::size_t n = view.messages.size();
  std::vector<std::size_t> chosen;  // newest first
  for (std::size_t i = n; i-- > 0 && chosen.size() < static_cast<std::size_t>(kLogShown);)
    if (pinned(view.messages[i])) chosen.push_back(i);
  const std::size_t pins = chosen.size();
  for (std::size_t i = n, others = 0; i-- > 0 && others + pins < static_cast<std::size_t>(kLogShown);)
    if (!pinned(view.messages[i])) chosen.push_back(i), ++others;
  std::sort(chosen.begin(), chosen.end());
  // Each chosen line as its wrapped rows, oldest first.
  std::vector<std::vector<StyledLine>> groups;
  std::size_t total = 0;
  for (const std::size_t i : chosen) {
    const LogLine& m = view.messages[i];
    std::string age = age_text(m.at_ms, view.now_ms);
    age.insert(0, 3 - std::min<std::size_t>(age.size(), 3), ' ');
    const int indent = static_cast<int>(age.size()) + 1;
    const auto parts = wrap(m.text, cols - indent);
    std::size_t consumed = 0;
    auto& group = groups.emplace_back();
    for (std::size_t k = 0; k < parts.size(); ++k) {
      StyledLine line;
      line.push_back({k == 0 ? age + " " : std::string(static_cast<std::size_t>(indent), ' '), kDim});
      const std::string& part = parts[k];
      // The sender's name (the first prefix_chars of the text) in the sender's colour.
      const std::size_t coloured = consumed < m.prefix_chars ? std::min(part.size(), m.prefix_chars - consumed) : 0;
      Style body = m.host ? Style{Color::yellow, Color::none, true, false, false} : Style{};
      if (coloured > 0) line.push_back({part.substr(0, coloured), player_style(m.from)});
      line.push_back({part.substr(coloured), body});
      consumed += part.size() + 1;
      group.push_back(std::move(line));
    }
    total += group.size();
  }
  // Too many rows: the oldest rows go, those of unpinned lines first.
  for (const bool drop_pinned : {false, true})
    for (std::size_t g = 0; g < groups.size() && total > static_cast<std::size_t>(rows); ++g) {
      if (pinned(view.messages[chosen[g]]) != drop_pinned) continue;
      const std::size_t cut = std::min(groups[g].size(), total - static_cast<std::size_t>(rows));
      groups[g].erase(groups[g].begin(), groups[g].begin() + static_cast<std::ptrdiff_t>(cut));
      total -= cut;
    }
  for (auto& group : groups)
    for (auto& line : group) out.push_back(std::move(line));
  return out;
}

std::vector<std::string> scoreboard_lines(const Snapshot& s, const ViewState& view, bool final_standings) {
  std::vector<const PlayerState*> order;
  for (const auto& p : s.players) order.push_back(&p);
  const auto score = [&](std::uint32_t id) {
    const auto it = view.scores.find(id);
    return it == view.scores.end() ? Score{} : it->second;
  };
  // By what each player earned in this match (its knocks' coins), not by coins in hand:
  // a late joiner's grant, a bank's interest or a thrifty shopper do not rank anyone up
  // (issue 37). Coins in hand, then lives, break ties.
  std::stable_sort(order.begin(), order.end(), [&](const PlayerState* a, const PlayerState* b) {
    if (score(a->id).coins_total != score(b->id).coins_total) return score(a->id).coins_total > score(b->id).coins_total;
    if (a->coins != b->coins) return a->coins > b->coins;
    return a->lives > b->lives;
  });
  std::vector<std::string> out;
  // Short enough for the field's width at 80x24 (45 columns).
  out.push_back((final_standings ? "Final standings at level " : "Standings after level ") + std::to_string(s.level) +
                ", by coins earned");
  char buf[160];
  std::snprintf(buf, sizeof buf, "%2s %-16s %6s %7s %6s %5s %9s", "#", "Player", "Level", "Earned", "Knocks", "Lives",
                "Coins");
  out.emplace_back(buf);
  int rank = 0;
  for (const PlayerState* p : order) {
    const Score sc = score(p->id);
    const std::string name = sanitize(p->name, 16) + (p->id == view.my_player_id ? "*" : "");
    std::snprintf(buf, sizeof buf, "%2d %-16s %6s %7s %6lld %5d %9s", ++rank, name.substr(0, 16).c_str(),
                  sim::with_thousands(sc.coins_level).c_str(), sim::with_thousands(sc.coins_total).c_str(),
                  static_cast<long long>(sc.knocks_total), p->lives, sim::with_thousands(p->coins).c_str());
    out.emplace_back(buf);
  }
  return out;
}

void tally_event(std::map<std::uint32_t, Score>& scores, const protocol::Event& e) {
  using protocol::EventKind;
  if (e.kind == EventKind::level_started && e.value <= 1) {
    scores.clear();  // a new match (play again)
  } else if (e.kind == EventKind::level_started || e.kind == EventKind::level_restarted) {
    for (auto& [id, sc] : scores) sc.coins_level = sc.knocks_level = 0;
  } else if (e.kind == EventKind::enemy_fell && e.b != 0) {
    if (scores.size() >= 256 && scores.count(e.b) == 0) return;  // bounded: ids come from the network
    Score& sc = scores[e.b];
    sc.coins_level += e.value;
    sc.coins_total += e.value;
    ++sc.knocks_level;
    ++sc.knocks_total;
  }
}

bool watching(const Snapshot& s, const ViewState& view) {
  const PlayerState* me = find_player(s, view.my_player_id);
  return me == nullptr || (me->lives <= 0 && !me->alive);
}

std::uint32_t followed(const Snapshot& s, const ViewState& view) {
  if (view.follow_id != 0 && find_player(s, view.follow_id) != nullptr) return view.follow_id;
  for (const auto& p : s.players)
    if (p.alive && p.id != view.my_player_id) return p.id;
  return 0;
}

std::uint32_t next_follow(const Snapshot& s, std::uint32_t current, std::uint32_t me) {
  std::vector<std::uint32_t> ids;
  for (const auto& p : s.players)
    if (p.id != me) ids.push_back(p.id);
  std::sort(ids.begin(), ids.end());
  if (ids.empty()) return 0;
  const auto it = std::upper_bound(ids.begin(), ids.end(), current);
  return it == ids.end() ? ids.front() : *it;
}

std::string footer_text(const Snapshot& s, const ViewState& view, int cols) {
  if (view.chat_open) {
    const std::string keys = "_   Enter: send   Esc: cancel";
    std::string draft = view.chat_draft;
    const int room = cols - 5 - static_cast<int>(keys.size());
    if (room > 0 && static_cast<int>(draft.size()) > room) draft = draft.substr(draft.size() - static_cast<std::size_t>(room));
    return "Say: " + draft + keys;
  }
  if (!view.replay_footer.empty()) return view.replay_footer;
  if (!view.notice.empty() && view.now_ms >= view.notice_ms && view.now_ms < view.notice_ms + kNoticeShowMs)
    return fit_footer(view.notice, cols);
  // The footer in words, then in short, each with the runs of spaces squeezed: the first
  // that fits. What the state adds (mouse steering, out of lives) stays in every form.
  std::vector<std::string> forms;
  const PlayerState* me = find_player(s, view.my_player_id);
  const bool out = me != nullptr && me->lives <= 0 && !me->alive;
  if (s.phase == Phase::play && watching(s, view)) {
    const PlayerState* f = find_player(s, followed(s, view));
    const std::string who = f != nullptr ? sanitize(f->name, 16) : "the match";
    forms.push_back("Watching " + who + "   Tab: next player   Chat: t   Quit: q" +
                    (out ? "   Out of lives: you play again when this match ends" : ""));
    forms.push_back("Watching " + who + "  Tab: next  Chat: t  Quit: q" + (out ? "  Out of lives: next match" : ""));
  } else if (s.phase == Phase::shop && out) {
    // The shop is the others': nothing to buy, nothing to ready (GAME_RULES: a player
    // with no lives left is out and watches until every player is out).
    forms.push_back("Out of lives: you play again when this match ends (all out)   Chat: t   Quit: q");
    forms.push_back("Out of lives: you play again next match  Chat: t  Quit: q");
  } else {
    const std::string steering = s.phase == Phase::play && view.mouse_steering ? "(mouse steering)" : "";
    forms.push_back(help_line(s.phase) + (steering.empty() ? "" : "   " + steering));
    if (s.phase == Phase::play) forms.push_back("Move: arrows/WASD/mouse  Fire: space  Chat: t  Quit: q" +
                                                (steering.empty() ? "" : "  " + steering));
  }
  for (const auto& form : forms)
    if (std::string fitted = fit_footer(form, cols); std::ssize(fitted) <= cols) return fitted;
  return fit_footer(forms.back(), cols);
}

std::string fit_footer(std::string text, int cols) {
  if (static_cast<int>(text.size()) <= cols) return text;
  std::string shorter;
  for (std::size_t i = 0; i < text.size(); ++i)
    if (!(text[i] == ' ' && i > 0 && text[i - 1] == ' ')) shorter += text[i];
  return shorter;
}

FrameLayout frame_layout(TerminalSize size, const ViewState& view, const Snapshot& snap) {
  FrameLayout L;
  const int cols = size.cols, rows = size.rows;
  L.footer_row = std::max(rows - 1, 0);
  if (cols < kMinCols || rows < kMinRows) {
    L.too_small = true;
    return L;
  }
  // Top layout: HUD, the wrapped legend, the arena, the log rows, the footer. The log
  // keeps two rows on a short terminal (80x24, the ssh terminal: every row given to it is
  // three columns of platform fewer), three from kRoomyRows rows; in the shop it takes
  // the rows the slide leaves (shop_rows_needed), at least one.
  const bool shop = snap.phase == Phase::shop;
  const int legend_rows =
      std::max<int>(1, static_cast<int>(legend_lines(snap, view, cols, false, kLegendTopMaxRows).size()));
  const int play_log_rows = rows >= kRoomyRows ? kTopLogRows : kTopLogRows - 1;
  const int free_rows = rows - 1 - legend_rows - 1;  // between the legend and the footer
  const int log_rows =
      shop ? std::clamp(free_rows - shop_rows_needed(snap, view, cols), 1, std::max(1, free_rows / 2)) : play_log_rows;
  const int top_area_rows = free_rows - log_rows;
  const Viewport top =
      fit_arena(1, 1 + legend_rows + 1, cols - 2, top_area_rows - 2, view.arena_width_u, view.arena_height_u);
  // Side layout: HUD, the arena on the left, the panel (legend, then log) on the right.
  const int panel_cols = std::clamp(cols / 4, 32, 44);
  const int side_cols = cols - panel_cols - 1;
  const Viewport side = fit_arena(1, 2, side_cols - 2, rows - 4, view.arena_width_u, view.arena_height_u);
  // The panel when the platform beside it keeps kSideMinFieldCols columns and three
  // fifths of the top layout's width (100x30 has it; at 80x24 it would shrink the
  // platform to 45 columns), and leaves the shop's slide its width.
  L.side = side.cols >= kSideMinFieldCols && side.cols * 5 >= top.cols * 4 && (!shop || side_cols >= kShopMinCols);
  if (L.side) {
    L.panel_col0 = cols - panel_cols;
    L.panel_cols = panel_cols;
    L.area_col0 = 0;
    L.area_row0 = 1;
    L.area_cols = side_cols;
    L.area_rows = rows - 2;
    L.arena = side;
    L.legend_row0 = 1;
    L.legend_rows = std::min<int>(static_cast<int>(snap.players.size()) + 1, rows / 2);
    L.log_row0 = L.legend_row0 + L.legend_rows + 1;
    L.log_rows = rows - 1 - L.log_row0;
    L.log_col0 = L.panel_col0;
    L.log_cols = panel_cols;
  } else {
    L.legend_row0 = 1;
    L.legend_rows = legend_rows;
    L.area_col0 = 0;
    L.area_row0 = 1 + legend_rows;
    L.area_cols = cols;
    L.area_rows = top_area_rows;
    L.arena = top;
    L.log_row0 = L.area_row0 + top_area_rows;
    L.log_rows = log_rows;
    L.log_col0 = 0;
    L.log_cols = cols;
  }
  return L;
}

}  // namespace fts::client
