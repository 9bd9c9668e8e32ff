// Where each part of the frame goes for a terminal size, and the text of the parts that
// must fit it: the HUD (abbreviated when narrow), the legend of players (a side panel when
// the terminal is wide enough, else wrapped rows on top), the message log with ages, the
// scoreboard and the footer. Pure: the tests lay out 80x24, 120x40 and 200x60.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "fts/protocol/snapshot.hpp"
#include "fts/sim/economy.hpp"
#include "ui/hud.hpp"
#include "ui/layout.hpp"
#include "ui/screen.hpp"
#include "ui/view.hpp"

namespace fts::client {

// Below this the platform and the HUD do not fit: the frame says so instead.
inline constexpr int kMinCols = 60;
inline constexpr int kMinRows = 20;
// Log lines kept by the client and shown at most.
inline constexpr std::size_t kLogKeep = 32;
// A notice (ViewState::notice) stays this long in the footer: long enough to read, even
// when a busy level's events push its log line off at once.
inline constexpr std::uint64_t kNoticeShowMs = 3000;
inline constexpr int kLogShown = 5;
// A host announcement keeps its place among the shown lines this long, however many
// lines come after it (a level's end brings a burst of them).
inline constexpr std::uint64_t kAnnouncePinnedMs = 20'000;

struct FrameLayout {
  bool too_small = false;
  bool side = false;  // legend and log in a panel on the right
  int hud_row = 0;
  int legend_row0 = 1, legend_rows = 0;  // top layout: the wrapped legend
  int panel_col0 = 0, panel_cols = 0;    // side layout: the panel's columns
  int log_row0 = 0, log_rows = 0, log_col0 = 0, log_cols = 0;
  int area_col0 = 0, area_row0 = 0, area_cols = 0, area_rows = 0;  // arena frame or shop text
  int footer_row = 0;
  Viewport arena;  // the platform inside its one-cell frame
};

// One piece of legend text and whose colour it takes.
struct Span {
  std::string text;
  Style style;
};
using StyledLine = std::vector<Span>;

FrameLayout frame_layout(TerminalSize size, const ViewState& view, const protocol::Snapshot& snap);

// "terminal too small: 50x15, need at least 60x20".
std::string too_small_text(TerminalSize size);

// The HUD for `cols` columns: the original's words, else abbreviated, else shorter still;
// the room code ("Room KXBQT") is the last part to go.
std::string hud_fit(const protocol::Snapshot& s, const ViewState& view, int cols);

// The legend as rows of at most `cols` characters: one player per row in the side panel
// (`one_per_row`), else packed and wrapped, names shortened until it fits in max_rows.
std::vector<StyledLine> legend_lines(const protocol::Snapshot& s, const ViewState& view, int cols,
                                     bool one_per_row, int max_rows);

// "12s" / "3m" / "1h": a log line's age.
std::string age_text(std::uint64_t at_ms, std::uint64_t now_ms);
// The newest log lines, each "age text" word-wrapped to `cols`, newest at the bottom, at
// most `rows` rows.
std::vector<StyledLine> log_lines(const ViewState& view, int cols, int rows);

// Splits text into rows of at most `cols` characters at spaces (long words are split).
std::vector<std::string> wrap(const std::string& text, int cols);

// The ranking: coins this level and in total, enemies knocked off, lives; by total coins.
std::vector<std::string> scoreboard_lines(const protocol::Snapshot& s, const ViewState& view, bool final_standings);

// The shop's slide for `me` wrapped to `width`, from the most spacious to the most
// compact: with blank lines between its groups; without them; without the Level, Coins
// and Lives lines the HUD repeats; without the items' explanations.
std::vector<std::vector<std::string>> shop_variants(const PlayerState& me, std::uint32_t level,
                                                    const sim::ShopTerms& terms, int width);
// The rows the shop needs at `cols` columns to show its most spacious slide, the
// standings and the result and ready lines (the top layout gives the log the rest).
int shop_rows_needed(const protocol::Snapshot& snap, const ViewState& view, int cols);

// A footer line that fits `cols` where it can: wider than that, the runs of spaces
// between key groups become single spaces.
std::string fit_footer(std::string text, int cols);
// The footer: what the keys do now (chat being typed, watching, the phase's controls).
std::string footer_text(const protocol::Snapshot& s, const ViewState& view, int cols);

// Counts an event into the score book: coins and knocks of the player credited with an
// enemy that fell; a new level starts the level's columns again.
void tally_event(std::map<std::uint32_t, Score>& scores, const protocol::Event& e);

// The player the view follows when watching: view.follow_id if still there, else the
// first player with a ball, else 0.
std::uint32_t followed(const protocol::Snapshot& s, const ViewState& view);
// The next player to follow after `current` (Tab), in id order, wrapping.
std::uint32_t next_follow(const protocol::Snapshot& s, std::uint32_t current, std::uint32_t me);
// Am I out of the match (or not in it): the view is watching.
bool watching(const protocol::Snapshot& s, const ViewState& view);

}  // namespace fts::client
