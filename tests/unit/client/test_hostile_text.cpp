// Issue 30: text another player wrote reaches this player's terminal as printable ASCII,
// whatever the server's cleaning and the decoder's check let through. Names come
// straight from snapshots, chat lines straight from protocol Chat messages (the client's
// own conversion, chat_log_line), the room code from a Welcome, and raw text is put into
// every text field of the view (as if a caller forgot to sanitise); the whole frame is
// rendered to the terminal's bytes (to_ansi, what term::Painter writes) at several
// sizes, in every phase.
#include <catch2/catch.hpp>

#include <string>
#include <string_view>
#include <vector>

#include "seed_situation.hpp"
#include "ui/chat_line.hpp"
#include "ui/hud.hpp"
#include "ui/panel.hpp"
#include "ui/render.hpp"
#include "ui/sanitize.hpp"
#include "ui/welcome_view.hpp"

using namespace fts::client;
using fts::protocol::BallKind;
using fts::protocol::BallState;
using fts::protocol::Event;
using fts::protocol::EventKind;
using fts::protocol::Phase;
using fts::protocol::Snapshot;

namespace {

// One of each kind issue 30 names (and a few more escapes), no spaces (names).
std::vector<std::string> hostile_texts() {
  return {
      "\x1b[2J\x1b[H" "csi",                                            // CSI: erase, home
      "\x1b]0;title\x07" "osc",                                         // OSC: the window title
      "\x1b]52;c;cHduZWQ=\x1b\\" "clip",                                // OSC 52: the clipboard
      "\xc2\x9b" "31m" "c1",                                            // U+009B, C1 CSI in UTF-8
      "\x9b" "2J" "\x9d" "0;t" "\x9c",                                  // C1 CSI, OSC, ST as lone bytes
      "b\bs\rc\x07" "d\x7f" "e\t" "f\n",                                // bare C0 and DEL
      std::string("nul\0x", 5),                                         // NUL
      "\xe6\x97\xa5\xe6\x9c\xac\xef\xbc\xa1" "cjk",                     // wide: two columns each
      "z\xe2\x80\x8b" "w\xe2\x80\x8d" "j\xef\xbb\xbf" "zw",             // zero-width
      "\xe2\x80\xae" "rlo\xe2\x81\xa6" "i\xe2\x81\xa7\xe2\x81\xa8\xe2\x81\xa9",  // bidi
      "e\xcc\x81\xcc\xa7\xcd\x9f" "comb",                               // combining marks
      "\xff\xfe\xc0\xaf\xed\xa0\x80\xf4\x90\x80\x80" "bad",             // invalid UTF-8
      "cut\xe6\x97",                                                    // a sequence cut short
      "\x1bP1$r\x1b\\" "dcs" "\x1b" "c" "\x1b" "7\x1b" "8",            // DCS, RIS, save/restore
      std::string(300, 'W') + "\xe6\x97\xa5\x1b[2J",                    // over-long
  };
}

// Why `bytes` could do more to a terminal than the client means ("": nothing): only
// printable ASCII and the CSI sequences to_ansi writes (ESC [, parameters 0-9 and ;, a
// final H or m: cursor position, SGR). No OSC, no other ESC, no C0 (not even CR or LF),
// no DEL, no byte >= 0x80.
std::string terminal_problem(std::string_view bytes) {
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if (c >= 0x20 && c < 0x7f) continue;
    const std::string at = " at byte " + std::to_string(i);
    if (c != 0x1b) return "byte " + std::to_string(c) + at;
    if (i + 1 >= bytes.size() || bytes[i + 1] != '[') return "ESC not followed by '['" + at;
    std::size_t j = i + 2;
    while (j < bytes.size() && std::string_view("0123456789;").find(bytes[j]) != std::string_view::npos) ++j;
    if (j >= bytes.size() || (bytes[j] != 'H' && bytes[j] != 'm')) return "a CSI sequence the renderer never writes" + at;
    i = j;
  }
  return "";
}

// The bytes without their CSI sequences: what takes a column each.
std::string visible(std::string_view bytes) {
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (bytes[i] == '\x1b' && i + 1 < bytes.size() && bytes[i + 1] == '[') {
      i += 2;
      while (i < bytes.size() && !(bytes[i] >= 0x40 && bytes[i] <= 0x7e)) ++i;
      continue;
    }
    out += bytes[i];
  }
  return out;
}

std::string joined(const Screen& s) {
  std::string out;
  for (const auto& line : s.lines()) out += line;
  return out;
}

BallState player_ball(std::uint32_t id, std::uint32_t owner, double x, double y) {
  BallState b;
  b.id = id;
  b.kind = BallKind::player;
  b.owner = owner;
  b.x = x;
  b.y = y;
  b.mass = 40;
  b.radius = 16;
  return b;
}

// Players 2 and 3 named `a` and `b` with me ("me", 1) in `phase`; in play their balls
// are on the field (their names beside them), and when `me_out` I am out (watching 2).
Snapshot scene(Phase phase, const std::string& a, const std::string& b, bool me_out) {
  Snapshot s = fts::client::test::seed_snapshot(phase);
  s.players[0].name = "me";
  if (me_out) s.players[0].lives = 0, s.players[0].alive = false;
  const std::pair<std::uint32_t, std::string> others[] = {{2, a}, {3, b}};
  for (const auto& [id, name] : others) {
    auto p = fts::client::test::seed_player();
    p.id = id;
    p.name = name;
    p.ready = id == 2;
    s.players.push_back(p);
  }
  if (phase == Phase::play) {
    if (!me_out) s.balls.push_back(player_ball(1, 1, 100, 150));
    s.balls.push_back(player_ball(2, 2, 250, 150));
    s.balls.push_back(player_ball(3, 3, 400, 100));
  }
  return s;
}

// The view a client has after a hostile player (2) talked, joined, bought and left, the
// host announced and the server sent a hostile room code; every other text field raw.
ViewState hostile_view(const Snapshot& s, const std::string& text, const std::string& other, bool chat_open,
                       bool replay) {
  ViewState view;
  fts::protocol::Welcome w;
  w.player_id = 1;
  w.match.tick_rate_hz = 100;
  w.room = text.substr(0, 16);
  show_welcome(view, w);
  view.now_ms = 10'000;
  view.names = {{2, text}, {3, other}, {9, other}};  // 9 left: only its name is known
  const std::pair<EventKind, std::uint32_t> events[] = {
      {EventKind::player_joined, 2}, {EventKind::purchase, 2}, {EventKind::player_fell, 3}, {EventKind::player_left, 9}};
  for (const auto& [kind, a] : events) {
    Event e;
    e.kind = kind;
    e.a = a;
    e.b = kind == EventKind::purchase ? 'm' : 0;
    view.messages.push_back(LogLine{describe_event(e, s, 1, &view.names), 9'000});
  }
  // Oldest first: the raw line (over-long: its rows go first when the log is full), then
  // 3's line, the host's, and 2's line, the newest.
  view.messages.push_back(LogLine{text + other, 9'200, 3, text.size() + other.size() + 5});
  view.messages.push_back(chat_log_line({1, 3, other, text}, 9'300, 120));
  view.messages.push_back(chat_log_line({2, 0, text, text}, 9'400, 120));  // "host"
  view.messages.push_back(chat_log_line({3, 2, text, other}, 9'900, 120));
  view.status = text;
  view.shop_result = other;
  view.follow_id = 2;
  view.chat_open = chat_open;
  view.chat_draft = text;
  if (replay) view.replay_footer = other;
  return view;
}

}  // namespace

TEST_CASE("hostile names and chat lines reach the terminal as printable ASCII only", "[client][sanitize][issue30]") {
  const auto texts = hostile_texts();
  // The check is not vacuous: each text written raw (as a client without its defences
  // would, between our own sequences) fails it; a frame of ours passes.
  for (const auto& text : texts) CHECK_FALSE(terminal_problem("\x1b[1;1H\x1b[0m" + text + "\x1b[0m").empty());
  CHECK(terminal_problem("\x1b[H\x1b[1;1H\x1b[0;1;4;33;100mok\x1b[0m").empty());
  const TerminalSize sizes[] = {{120, 40}, {80, 24}, {60, 20}, {200, 50}, {50, 15}};
  int frames = 0;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const std::string& text = texts[i];
    const std::string& other = texts[(i + 1) % texts.size()];
    for (const Phase phase : {Phase::lobby, Phase::play, Phase::shop, Phase::over}) {
      for (const int variant : {0, 1, 2}) {  // 1: I am out, typing a line; 2: a replay's footer
        const Snapshot s = scene(phase, text, other, variant == 1);
        ViewState view = hostile_view(s, text, other, variant == 1, variant == 2);
        for (const TerminalSize size : sizes) {
          for (const bool color : {true, false}) {
            view.color = color;
            const Screen screen = render(s, s, 0, size, view);
            const std::string bytes = to_ansi(screen, color);
            INFO("text " << i << ", phase " << static_cast<int>(phase) << ", variant " << variant << ", " << size.cols
                         << "x" << size.rows << (color ? " colour" : " plain"));
            REQUIRE(terminal_problem(bytes).empty());
            // One byte a column: every cell one printable byte, the rows exactly as wide
            // as the terminal (a wide or zero-width character would shift what follows).
            REQUIRE(visible(bytes) == joined(screen));
            REQUIRE(visible(bytes).size() == static_cast<std::size_t>(size.cols) * static_cast<std::size_t>(size.rows));
            ++frames;
          }
        }
        // Where the hostile player shows, it shows cleaned: the legend, its chat line.
        if (variant != 0) continue;
        const Screen wide = render(s, s, 0, {200, 50}, view);
        const std::string shown = joined(wide);
        const std::string name = sanitize(text, 16);
        std::string picture;
        for (const auto& line : wide.lines()) picture += line + "\n";
        INFO("text " << i << ", phase " << static_cast<int>(phase) << ":\n" << picture);
        CHECK(shown.find(name.substr(0, 6)) != std::string::npos);
        CHECK(shown.find(name + ":") != std::string::npos);  // its chat line (wrapped after the name if long)
        CHECK(shown.find(sanitize(other, 120).substr(0, 20)) != std::string::npos);
      }
    }
  }
  CHECK(frames == static_cast<int>(texts.size()) * 4 * 3 * 5 * 2);
}

TEST_CASE("a chat line heard is sanitised by the client itself, name and text", "[client][sanitize][issue30]") {
  const LogLine l = chat_log_line({7, 4, "\x1b]0;x\x07\xe2\x80\xae" "bob", "hi\x1b[2J \xe6\x97\xa5\xe6\x9c\xac\xc2\x9b" "m"}, 5, 120);
  CHECK(l.text == "]0;x?bob: hi[2J ???m");
  CHECK(l.prefix_chars == std::string("]0;x?bob:").size());  // the name's colour ends at its colon
  CHECK(l.from == 4);
  CHECK_FALSE(l.host);
  const LogLine host = chat_log_line({8, 0, "\x1b[31mroot", "restart\x07 in 5"}, 5, 120);
  CHECK(host.text == "host: restart in 5");
  CHECK(host.host);
  CHECK(chat_log_line({9, 4, "a", std::string(500, 'x')}, 5, 120).text.size() == 3 + 120);
  // The placeholders of sanitize: one per character, whatever its width or kind.
  CHECK(sanitize("\xe6\x97\xa5\xe6\x9c\xac\xef\xbc\xa1" "cjk") == "???cjk");
  CHECK(sanitize("z\xe2\x80\x8b" "w\xe2\x80\x8d" "j\xef\xbb\xbf" "zw") == "z?w?j?zw");
  CHECK(sanitize("\xe2\x80\xae" "rlo\xe2\x81\xa6" "i\xe2\x81\xa7\xe2\x81\xa8\xe2\x81\xa9") == "?rlo?i???");
  CHECK(sanitize("e\xcc\x81\xcc\xa7\xcd\x9f" "comb") == "e???comb");
  CHECK(sanitize("\xff\xfe\xc0\xaf\xed\xa0\x80\xf4\x90\x80\x80" "bad") == "?????bad");
  CHECK(sanitize("\x9b" "2J" "\x9d" "0;t" "\x9c") == "?2J?0;t?");
  CHECK(sanitize("cut\xe6\x97") == "cut?");
}

TEST_CASE("a hostile room code in the welcome is shown cleaned", "[client][sanitize][issue30]") {
  ViewState view;
  fts::protocol::Welcome w;
  w.room = "\x1b]0;x\x07\xe6\x97\xa5" "ABCDE";
  show_welcome(view, w);
  CHECK(view.room == "Room ]0;x?ABC");
  w.spectator = true;
  show_welcome(view, w);
  CHECK(view.room == "Watching ]0;x?ABC");
}
