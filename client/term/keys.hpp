// Keyboard input, pure: bytes from the terminal become key events (legacy sequences and
// the kitty keyboard protocol's CSI u form with press/repeat/release), and a hold tracker
// turns them into thrust. Legacy terminals send no key-up: a key counts as held while it
// repeats, and is let go after a short release time-out.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fts/protocol/snapshot.hpp"

namespace fts::client {

// focus_in / focus_out: the terminal window gained or lost the focus (xterm's focus
// reporting, mode 1004, turned on with the mouse): CSI I and CSI O.
enum class Key : std::uint8_t {
  none, up, down, left, right, space, enter, escape, ctrl_c, character, tab, backspace, mouse, focus_in, focus_out
};
enum class KeyAction : std::uint8_t { press, repeat, release };
struct KeyEvent;
// A report of the pointer or of the window's focus, not a key a person pressed.
bool is_report(const KeyEvent& e);

struct KeyEvent {
  Key key = Key::none;
  char ch = 0;  // Key::character: the lower-case ASCII letter or symbol
  KeyAction action = KeyAction::press;
  bool kitty = false;  // came in the kitty protocol's form: releases will be reported
  // Key::mouse (xterm SGR reporting): the cell under the pointer (0-based), the button
  // (0 left, 1 middle, 2 right, 3 none, 64/65 wheel) and whether it is a motion report.
  int col = 0, row = 0, button = 3;
  bool motion = false;
  char text = 0;  // Key::character: the character as typed (case kept), for the chat line
  bool operator==(const KeyEvent& o) const {
    return key == o.key && ch == o.ch && action == o.action && kitty == o.kitty && col == o.col && row == o.row &&
           button == o.button && motion == o.motion;
  }
};

// The kitty keyboard protocol: push flags disambiguate (1) | report event types (2) |
// report all keys as escape codes (8, needed for releases of plain letters), pop them,
// and the query whose answer (CSI ? flags u) tells that the terminal supports it. The
// query is followed by the primary device attributes request (DA1, CSI c), which every
// terminal answers: a DA1 answer without a kitty answer before it means no kitty (the
// protocol's documented detection), and the flags are pushed only after an answer.
inline constexpr int kKittyFlags = 1 | 2 | 8;
std::string kitty_push();
inline constexpr std::string_view kKittyPop = "\x1b[<u";
inline constexpr std::string_view kKittyQuery = "\x1b[?u";
inline constexpr std::string_view kDeviceQuery = "\x1b[c";
// xterm mouse reporting: any-motion tracking (1003) in the SGR form (1006), with focus
// reporting (1004: mouse steering ends when the window loses the focus), and off again.
inline constexpr std::string_view kMouseOn = "\x1b[?1003h\x1b[?1006h\x1b[?1004h";
inline constexpr std::string_view kMouseOff = "\x1b[?1004l\x1b[?1006l\x1b[?1003l";
// What entering game mode writes: the alternate screen, a hidden cursor, a clear; with
// kitty_query the kitty query and DA1 (never the push: see above); with mouse, kMouseOn.
std::string enter_bytes(bool kitty_query, bool mouse);

class KeyDecoder {
 public:
  // Decodes what it can; an incomplete escape sequence waits for more bytes.
  std::vector<KeyEvent> feed(std::string_view bytes);
  // A lone ESC with nothing after it for a while is the Escape key.
  std::vector<KeyEvent> flush();
  bool pending() const { return !buffer_.empty(); }
  // The terminal answered the kitty query with "report event types" set (after our
  // push): it reports key release events.
  bool kitty_supported() const { return kitty_supported_; }
  // The terminal answered the kitty query (any flags) before its DA1 answer: it speaks
  // the protocol, so the flags may be pushed.
  bool kitty_answered() const { return kitty_answered_; }
  // The terminal answered DA1 (CSI ? ... c).
  bool device_answered() const { return device_answered_; }

 private:
  std::string buffer_;
  bool kitty_supported_ = false;
  bool kitty_answered_ = false;
  bool device_answered_ = false;
};

enum class Direction : std::uint8_t { up, down, left, right };
std::optional<Direction> direction_of(const KeyEvent& e);

// A tap is a short impulse; a key the terminal repeats is a hold. Without release events
// a repeat is told from a new tap by its distance to the previous event of that key.
struct HoldConfig {
  std::uint64_t tap_ms = 130;          // a first press: a short impulse
  std::uint64_t repeat_hold_ms = 120;  // after a repeat: a little more than the repeat interval
  std::uint64_t repeat_gap_ms = 650;   // a press this soon after the last one is the key's auto-repeat
};

class HoldTracker {
 public:
  explicit HoldTracker(HoldConfig config = {}) : config_(config) {}
  // A direction key event at now_ms.
  void on_key(Direction d, const KeyEvent& e, std::uint64_t now_ms);
  bool held(Direction d, std::uint64_t now_ms) const;
  // Thrust per axis: -1, 0 or +1 (x right, y up).
  int move_x(std::uint64_t now_ms) const;
  int move_y(std::uint64_t now_ms) const;
  void release_all() { until_ms_.fill(0); }

 private:
  HoldConfig config_;
  std::array<std::uint64_t, 4> until_ms_{};  // held while now < until; max: until released
  std::array<std::uint64_t, 4> last_ms_{};   // the last press or repeat of each direction
  std::array<bool, 4> seen_{};
};

// Mouse steering, agar.io's way with the game's per-axis thrust: toward the pointer on
// each axis where it is farther than dead_u from the ball's centre. Returns {x, y} in
// -1..1 (x right, y up).
struct Steer {
  int x = 0, y = 0;
  bool operator==(const Steer&) const = default;
};
Steer steer_toward(double ball_x_u, double ball_y_u, double pointer_x_u, double pointer_y_u, double dead_u);

// What a key means in a phase of the game.
enum class ActionKind : std::uint8_t { none, move, fire, buy, ready, quit, chat, follow, pointer };
struct Action {
  ActionKind kind = ActionKind::none;
  char item = 0;  // buy: m s a r l x b
};
Action action_of(const KeyEvent& e, protocol::Phase phase);

}  // namespace fts::client
