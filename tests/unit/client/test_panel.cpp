// The frame's layout with eight players at the sizes players use, the message log, the
// scoreboard, the refusals in words and the small-terminal warning.
#include <catch2/catch.hpp>

#include <cmath>

#include "field_geometry.hpp"
#include "seed_situation.hpp"
#include "fts/protocol/codes.hpp"
#include "fts/sim/shop_text.hpp"
#include "ui/hud.hpp"
#include "ui/palette.hpp"
#include "ui/panel.hpp"
#include "ui/render.hpp"

using namespace fts::client;
using fts::protocol::BallKind;
using fts::protocol::BallState;
using fts::protocol::Event;
using fts::protocol::EventKind;
using fts::protocol::Phase;
using fts::protocol::Snapshot;

namespace {

const char* const kNames[8] = {"ann", "bob", "charlotte", "dmitri", "eve", "sixteen_letters_", "gwen", "hiro"};

Snapshot eight_players() {
  Snapshot s = fts::client::test::seed_snapshot(Phase::play);
  s.players.clear();
  for (std::uint32_t i = 0; i < 8; ++i) {
    auto p = fts::client::test::seed_player();
    p.id = i + 1;
    p.name = kNames[i];
    p.coins = 1234 * (i + 1);
    p.lives = 3;
    s.players.push_back(p);
    BallState b;
    b.id = 100 + i;
    b.kind = BallKind::player;
    b.owner = i + 1;
    b.x = 40 + 60.0 * i;
    b.y = i % 2 == 0 ? 80 : 220;
    b.mass = 40;
    b.radius = 16;
    s.balls.push_back(b);
  }
  return s;
}

ViewState view_of(std::uint64_t now_ms) {
  ViewState v;
  v.my_player_id = 1;
  v.color = false;
  v.ping_ms = 23;
  v.loss_percent = 0.5;
  v.now_ms = now_ms;
  for (int i = 0; i < 7; ++i)
    v.messages.push_back(LogLine{"message number " + std::to_string(i), now_ms - 1000 * static_cast<std::uint64_t>(7 - i)});
  return v;
}

std::string all_text(const Screen& s) {
  std::string out;
  for (const auto& l : s.lines()) out += l + "\n";
  return out;
}

}  // namespace

TEST_CASE("with 8 players nothing is cut at 80x24, 120x40 and 200x60", "[client][layout]") {
  const Snapshot snap = eight_players();
  const ViewState view = view_of(100'000);
  for (const TerminalSize size : {TerminalSize{80, 24}, TerminalSize{120, 40}, TerminalSize{200, 60}}) {
    INFO(size.cols << "x" << size.rows);
    const FrameLayout L = frame_layout(size, view, snap);
    REQUIRE_FALSE(L.too_small);
    const Screen screen = render(snap, snap, 0, size, view);
    const std::string text = all_text(screen);
    // The HUD in full (or its abbreviation) on the first row.
    const std::string hud = hud_fit(snap, view, size.cols);
    CHECK(screen.line(0).rfind(hud, 0) == 0);
    CHECK(hud.find("Lives") != std::string::npos);
    // Every player in the legend with its full name, coins and lives.
    for (const auto& p : snap.players) {
      INFO(p.name);
      CHECK(text.find(p.name) != std::string::npos);
      CHECK(text.find(fts::sim::with_thousands(p.coins) + "c 3L") != std::string::npos);
    }
    // Every name on the field, on the row just above its ball's top cell (cut to
    // kNameOnFieldChars).
    const Viewport& v = L.arena;
    for (const auto& b : snap.balls) {
      const std::string name = std::string(kNames[b.owner - 1]).substr(0, kNameOnFieldChars);
      const int row = fts::client::test::top_row(v, b) - 1;
      INFO(name << " at row " << row);
      CHECK(screen.line(row).find(name) != std::string::npos);
    }
    // The platform stays clear of the panel and the text rows.
    CHECK(v.row0 >= 2);
    CHECK(v.row0 + v.rows < L.footer_row);
    if (L.side) CHECK(v.col0 + v.cols < L.panel_col0);
    // The log: the newest line at the bottom with its age; the oldest beyond 5 dropped.
    // (At 80x24 the log has the two rows the platform leaves it: the newest two.)
    CHECK(text.find("1s message number 6") != std::string::npos);
    CHECK(text.find("2s message number 5") != std::string::npos);
    if (L.log_rows >= 5) CHECK(text.find("5s message number 2") != std::string::npos);
    CHECK(text.find("message number 1") == std::string::npos);
    CHECK(text.find("message number 6") > text.find("message number 5"));
    // The footer fits.
    CHECK(footer_text(snap, view, size.cols).size() <= static_cast<std::size_t>(size.cols));
    CHECK(screen.line(L.footer_row).find("Chat: t") != std::string::npos);
  }
  CHECK(frame_layout({120, 40}, view, snap).side);
}

TEST_CASE("player colours are stable by id and differ for eight players", "[client][layout]") {
  Snapshot snap = eight_players();
  ViewState view = view_of(0);
  view.color = true;
  const Screen screen = render(snap, snap, 0, {120, 40}, view);
  const Viewport v = frame_layout({120, 40}, view, snap).arena;
  std::vector<Color> seen;
  for (const auto& b : snap.balls) {
    const Color c = screen.at(v.col_of(b.x) - 2, v.row_of(b.y)).style.fg;
    CHECK(c == player_color(b.owner));
    CHECK(std::find(seen.begin(), seen.end(), c) == seen.end());
    seen.push_back(c);
  }
  CHECK(screen.at(v.col_of(snap.balls[0].x) - 2, v.row_of(snap.balls[0].y)).ch == kMyBallChar);
}

TEST_CASE("a terminal below 60x20 says so instead of drawing the field", "[client][layout]") {
  const Snapshot snap = eight_players();
  const ViewState view = view_of(0);
  for (const TerminalSize size : {TerminalSize{59, 30}, TerminalSize{100, 19}, TerminalSize{30, 10}}) {
    const std::string text = all_text(render(snap, snap, 0, size, view));
    INFO(text);
    CHECK(text.find("terminal too small: " + std::to_string(size.cols) + "x" + std::to_string(size.rows)) !=
              std::string::npos);
    CHECK(text.find("need at least 60x20") != std::string::npos);
  }
  CHECK_FALSE(frame_layout({60, 20}, view, snap).too_small);
}

TEST_CASE("the message log keeps ages and wraps long lines", "[client][log]") {
  CHECK(age_text(1000, 1000) == "0s");
  CHECK(age_text(1000, 60'999) == "59s");
  CHECK(age_text(0, 61'000) == "1m");
  CHECK(age_text(0, 7'300'000) == "2h");
  CHECK(age_text(5000, 1000) == "0s");  // clock went back: no wrap-around
  ViewState v;
  v.now_ms = 10'000;
  v.messages.push_back(LogLine{"bob: a rather long line that cannot fit in twenty columns", 9'000, 2, 4});
  const auto lines = log_lines(v, 24, 10);
  REQUIRE(lines.size() >= 3);
  CHECK(lines[0][0].text == " 1s ");
  CHECK(lines[0][1].text == "bob:");  // the sender's name in its colour
  CHECK(lines[0][1].style.fg == player_color(2));
  for (const auto& l : lines) {
    std::size_t n = 0;
    for (const auto& span : l) n += span.text.size();
    CHECK(n <= 24);
  }
  CHECK(log_lines(v, 24, 2).size() == 2);  // bounded by the rows given: the newest rows
  CHECK(wrap("abcdefghij", 4) == std::vector<std::string>{"abcd", "efgh", "ij"});
}

TEST_CASE("a host announcement stays in the log while the level's own lines pour in", "[client][hud][announce]") {
  // Issue 26: announced at level end, it was pushed out of the 5 lines within a second.
  ViewState v;
  v.now_ms = 20'000;
  v.messages.push_back(LogLine{"old line", 18'000});
  v.messages.push_back(LogLine{"host: server restarts at noon", 19'000, 0, 5, true});
  for (int i = 0; i < 8; ++i)
    v.messages.push_back(LogLine{"event line " + std::to_string(i), 19'100 + 100 * static_cast<std::uint64_t>(i)});
  const auto text_of = [](const StyledLine& l) {
    std::string t;
    for (const auto& span : l) t += span.text;
    return t;
  };
  const auto shown = [&](int rows) {
    std::vector<std::string> out;
    for (const auto& l : log_lines(v, 60, rows)) out.push_back(text_of(l));
    return out;
  };
  auto lines = shown(10);
  REQUIRE(lines.size() == static_cast<std::size_t>(kLogShown));
  CHECK(lines[0] == " 1s host: server restarts at noon");  // pinned, in its place in time
  CHECK(lines[4].find("event line 7") != std::string::npos);  // the newest lines go on
  CHECK(lines[1].find("event line 4") != std::string::npos);
  lines = shown(2);  // fewer rows than lines: the announcement keeps one of them
  REQUIRE(lines.size() == 2);
  CHECK(lines[0].find("server restarts at noon") != std::string::npos);
  CHECK(lines[1].find("event line 7") != std::string::npos);
  // Once its time is up it is an old line like any other.
  v.now_ms = 19'000 + kAnnouncePinnedMs + 1;
  lines = shown(10);
  REQUIRE(lines.size() == static_cast<std::size_t>(kLogShown));
  for (const auto& l : lines) CHECK(l.find("server restarts") == std::string::npos);
}

TEST_CASE("refusals are said in words", "[client][hud]") {
  const auto me = fts::client::test::seed_player();  // 286 coins; mass costs 35, rockets 1,000,000
  CHECK(refusal_text("coins", "", 'r', &me) == "not enough coins: rockets costs 1,000,000, you have 286");
  CHECK(refusal_text("phase", "wrong_phase", 'm', &me) == "not now: the shop is closed");
  CHECK(refusal_text("owned", "", 'b', &me) == "you already have bank: it is bought once");
  CHECK(refusal_text("dead", "", 'm', &me) == "you are out of the match: watching");
  CHECK(refusal_text("rate", "", 0, nullptr) == "too many chat lines: wait a moment");
  CHECK(refusal_text("weird", "the server says \x1b[31mno", 0, nullptr) == "the server says [31mno");
  CHECK(refusal_text("weird", "", 0, nullptr) == "refused (weird)");
}

TEST_CASE("the scoreboard ranks by coins earned and counts knocks per level", "[client][score]") {
  Snapshot s = eight_players();
  ViewState view = view_of(0);
  tally_event(view.scores, Event{1, 1, EventKind::enemy_fell, 50, 2, 40});
  tally_event(view.scores, Event{2, 2, EventKind::enemy_fell, 51, 2, 45});
  tally_event(view.scores, Event{3, 3, EventKind::enemy_fell, 52, 0, 0});  // nobody credited
  CHECK(view.scores[2].coins_level == 85);
  CHECK(view.scores[2].knocks_total == 2);
  tally_event(view.scores, Event{4, 4, EventKind::level_started, 0, 0, 4});
  CHECK(view.scores[2].coins_level == 0);
  CHECK(view.scores[2].coins_total == 85);
  const auto board = scoreboard_lines(s, view, true);
  REQUIRE(board.size() == 10);
  CHECK(board[0] == "Final standings at level 3, by coins earned");
  CHECK(board[2].find("bob") != std::string::npos);  // the only one who earned: first
  CHECK(board[2].find("  85 ") != std::string::npos);
  CHECK(board[3].find("hiro") != std::string::npos);  // then by coins in hand
  CHECK(board[9].find("ann*") != std::string::npos);  // you, marked
  tally_event(view.scores, Event{5, 5, EventKind::level_started, 0, 0, 1});  // play again
  CHECK(view.scores.empty());
  // At game over the standings replace the field.
  s.phase = Phase::over;
  const std::string text = all_text(render(s, s, 0, {120, 40}, view));
  CHECK(text.find("Final standings") != std::string::npos);
  CHECK(text.find("Press Enter to play again") != std::string::npos);
}

TEST_CASE("the shop shows its countdown, the standings and a watcher's note", "[client][countdown]") {
  Snapshot s = eight_players();
  s.phase = Phase::shop;
  s.deadline_tick = s.tick + 1450;
  ViewState view = view_of(0);
  std::string text = all_text(render(s, s, 0, {120, 40}, view));
  CHECK(text.find("Next level in 15 s.") != std::string::npos);
  CHECK(text.find("Standings after level 3") != std::string::npos);
  // Eight names do not fit on the ready line at 80 columns: a count and who is shopping.
  for (auto& p : s.players) p.ready = p.id != 1;
  text = all_text(render(s, s, 0, {80, 24}, view));
  CHECK(text.find("Ready: 7 of 8; shopping: ann") != std::string::npos);
  s.players[0].lives = 0;
  s.players[0].alive = false;
  text = all_text(render(s, s, 0, {120, 40}, view));
  CHECK(text.find("You are out: watching the others shop.") != std::string::npos);
}

TEST_CASE("watching: Tab cycles the players and the footer says so", "[client][watch]") {
  Snapshot s = eight_players();
  s.players[0].lives = 0;
  s.players[0].alive = false;
  ViewState view = view_of(0);
  CHECK(watching(s, view));
  CHECK(followed(s, view) == 2);
  CHECK(next_follow(s, 2, 1) == 3);
  CHECK(next_follow(s, 8, 1) == 2);  // wraps, skipping yourself
  view.follow_id = 4;
  CHECK(footer_text(s, view, 120).rfind("Watching dmitri   Tab: next player", 0) == 0);
  const std::string text = all_text(render(s, s, 0, {120, 40}, view));
  CHECK(text.find("[dmitri]") != std::string::npos);
  view.chat_open = true;
  view.chat_draft = "gg";
  CHECK(footer_text(s, view, 120) == "Say: gg_   Enter: send   Esc: cancel");
  // A notice takes the footer for kNoticeShowMs, then the keys come back.
  view.chat_open = false;
  view.notice = "Room moved to another server: playing on";
  view.notice_ms = 10'000;
  view.now_ms = 10'000;
  CHECK(footer_text(s, view, 80) == view.notice);
  view.now_ms = 10'000 + kNoticeShowMs - 1;
  CHECK(footer_text(s, view, 80) == view.notice);
  view.now_ms = 10'000 + kNoticeShowMs;
  CHECK(footer_text(s, view, 120).rfind("Watching dmitri", 0) == 0);
}

TEST_CASE("Codes: the client's text for a result code is the table's sentence where it has one",
          "[client][codes]") {
  // A code the protocol gives a sentence (codes.hpp result_sentence) reads as that
  // sentence whatever the server wrote; every other code has words of the client's own,
  // but the two whose words are the server's (a field, a spectator's command).
  for (const auto& row : fts::protocol::kResultCodes) {
    if (row.code == fts::protocol::ResultCode::ok) continue;
    const std::string name(row.name);
    INFO("result code " << name);
    const auto sentence = fts::protocol::result_sentence(row.code);
    if (!sentence.empty()) CHECK(refusal_text(name, "something else", 0, nullptr) == sentence);
    const bool servers_words = row.code == fts::protocol::ResultCode::field || row.code == fts::protocol::ResultCode::spectator;
    CHECK((refusal_text(name, "", 'm', nullptr) == "refused (" + name + ")") == servers_words);
  }
}
