#include "term/keys.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

namespace fts::client {

std::string kitty_push() { return "\x1b[>" + std::to_string(kKittyFlags) + "u"; }

std::string enter_bytes(bool kitty_query, bool mouse) {
  std::string out = "\x1b[?1049h\x1b[?25l\x1b[2J";
  if (kitty_query) {
    out += kKittyQuery;
    out += kDeviceQuery;
  }
  if (mouse) out += kMouseOn;
  return out;
}

namespace {

KeyEvent from_char(unsigned char c) {
  KeyEvent e;
  if (c == 0x03) e.key = Key::ctrl_c;
  else if (c == '\r' || c == '\n') e.key = Key::enter;
  else if (c == ' ') e.key = Key::space;
  else if (c == 0x1b) e.key = Key::escape;
  else if (c == '\t') e.key = Key::tab;
  else if (c == 0x7f || c == 0x08) e.key = Key::backspace;
  else if (c >= 0x21 && c < 0x7f) {
    e.key = Key::character;
    e.ch = static_cast<char>(std::tolower(c));
    e.text = static_cast<char>(c);
  }
  return e;
}

// Splits "a:b;c:d" into fields of sub-parameters (missing numbers are -1).
std::vector<std::vector<long>> parse_params(std::string_view p) {
  std::vector<std::vector<long>> fields(1);
  long cur = -1;
  for (char ch : p) {
    if (ch >= '0' && ch <= '9') {
      cur = (cur < 0 ? 0 : cur) * 10 + (ch - '0');
      if (cur > 10'000'000) cur = 10'000'000;
    } else if (ch == ':' || ch == ';') {
      fields.back().push_back(cur);
      cur = -1;
      if (ch == ';') fields.emplace_back();
    }
  }
  fields.back().push_back(cur);
  return fields;
}

long param(const std::vector<std::vector<long>>& f, std::size_t i, std::size_t j, long def) {
  if (i >= f.size() || j >= f[i].size() || f[i][j] < 0) return def;
  return f[i][j];
}

// A character outside ASCII, typed: the chat line shows and sends it as '?' (the screen
// and the wire carry printable ASCII); it is no command key.
KeyEvent typed_elsewhere() {
  KeyEvent e;
  e.key = Key::character;
  e.text = '?';
  return e;
}

// What a CSI sequence answered: nothing, the kitty query (with its flags), or DA1.
struct Reply {
  enum Kind : std::uint8_t { none, kitty, device } kind = none;
  long kitty_flags = 0;
};

// One complete CSI sequence: parameters (without a leading private marker) and final byte.
std::optional<KeyEvent> decode_csi(std::string_view params, char final_byte, Reply& reply) {
  if (!params.empty() && params[0] == '<') {
    // SGR mouse: CSI < button ; column ; row M (press, motion) or m (release), 1-based.
    if (final_byte != 'M' && final_byte != 'm') return std::nullopt;
    const auto f = parse_params(params.substr(1));
    if (f.size() != 3) return std::nullopt;
    const long b = param(f, 0, 0, -1), col = param(f, 1, 0, -1), row = param(f, 2, 0, -1);
    if (b < 0 || col < 1 || row < 1) return std::nullopt;
    KeyEvent e;
    e.key = Key::mouse;
    e.button = static_cast<int>(b & ~(4 | 8 | 16 | 32));  // without shift/alt/ctrl/motion
    e.motion = (b & 32) != 0;
    e.action = final_byte == 'm' ? KeyAction::release : KeyAction::press;
    e.col = static_cast<int>(col - 1);
    e.row = static_cast<int>(row - 1);
    return e;
  }
  if (!params.empty() && params[0] == '?') {
    // CSI ? flags u: the kitty query's answer; CSI ? attributes c: DA1's.
    if (final_byte == 'u') reply = Reply{Reply::kitty, param(parse_params(params.substr(1)), 0, 0, 0)};
    if (final_byte == 'c') reply.kind = Reply::device;
    return std::nullopt;
  }
  if (params.empty() && (final_byte == 'I' || final_byte == 'O')) {  // focus reporting (1004)
    KeyEvent e;
    e.key = final_byte == 'I' ? Key::focus_in : Key::focus_out;
    return e;
  }
  const auto f = parse_params(params);
  const long mods = param(f, 1, 0, 1) - 1;  // bits: 1 shift, 2 alt, 4 ctrl
  const long type = param(f, 1, 1, -1);     // kitty event type: 1 press, 2 repeat, 3 release
  KeyEvent e;
  e.kitty = type > 0;
  e.action = type == 2 ? KeyAction::repeat : type == 3 ? KeyAction::release : KeyAction::press;
  switch (final_byte) {
    case 'A': e.key = Key::up; return e;
    case 'B': e.key = Key::down; return e;
    case 'C': e.key = Key::right; return e;
    case 'D': e.key = Key::left; return e;
    case 'u': {
      e.kitty = true;  // CSI u is only sent under the kitty protocol
      const long code = param(f, 0, 0, 0);
      if (code == 13 || code == 57414) e.key = Key::enter;
      else if (code == 32) e.key = Key::space;
      else if (code == 27) e.key = Key::escape;
      else if (code == 9) e.key = Key::tab;
      else if (code == 127 || code == 8) e.key = Key::backspace;
      else if (code == 'c' && (mods & 4) != 0) e.key = Key::ctrl_c;
      else if (code == 57417) e.key = Key::left;  // keypad arrows
      else if (code == 57418) e.key = Key::right;
      else if (code == 57419) e.key = Key::up;
      else if (code == 57420) e.key = Key::down;
      else if (code > 0x20 && code < 0x7f) {
        e.key = Key::character;
        e.ch = static_cast<char>(std::tolower(static_cast<int>(code)));
        e.text = (mods & 1) != 0 ? static_cast<char>(std::toupper(static_cast<int>(code))) : e.ch;
      } else if (code >= 0xa0 && code < 0xe000) {
        return typed_elsewhere();  // a letter outside ASCII (below the private-use keys)
      } else {
        return std::nullopt;  // modifiers alone, function keys: not ours
      }
      if ((mods & 4) != 0 && e.key == Key::character) return std::nullopt;
      return e;
    }
    default: return std::nullopt;
  }
}

}  // namespace

std::vector<KeyEvent> KeyDecoder::feed(std::string_view bytes) {
  buffer_ += bytes;
  std::vector<KeyEvent> out;
  std::size_t i = 0;
  while (i < buffer_.size()) {
    const auto c = static_cast<unsigned char>(buffer_[i]);
    if (c >= 0xc2 && c <= 0xf4) {  // a UTF-8 letter: one '?' typed, never dropped unseen
      const std::size_t n = c < 0xe0 ? 2 : c < 0xf0 ? 3 : 4;
      std::size_t k = 1;
      while (k < n && i + k < buffer_.size() && (static_cast<unsigned char>(buffer_[i + k]) & 0xc0) == 0x80) ++k;
      if (k < n && i + k >= buffer_.size()) break;  // the rest of it is still on its way
      out.push_back(typed_elsewhere());
      i += k;  // a sequence cut short ends at the byte that broke it
      continue;
    }
    if (c != 0x1b) {
      const KeyEvent e = from_char(c);
      if (e.key != Key::none) out.push_back(e);
      ++i;
      continue;
    }
    if (i + 1 >= buffer_.size()) break;  // ESC alone so far: wait (flush() decides)
    const char kind = buffer_[i + 1];
    if (kind == 'O') {  // SS3: application-mode arrows
      if (i + 2 >= buffer_.size()) break;
      const char fb = buffer_[i + 2];
      KeyEvent e;
      if (fb == 'A') e.key = Key::up;
      else if (fb == 'B') e.key = Key::down;
      else if (fb == 'C') e.key = Key::right;
      else if (fb == 'D') e.key = Key::left;
      else if (fb == 'M') e.key = Key::enter;
      if (e.key != Key::none) out.push_back(e);
      i += 3;
      continue;
    }
    if (kind != '[') {  // Alt+key or a stray ESC: take the ESC as Escape
      out.push_back(KeyEvent{Key::escape});
      ++i;
      continue;
    }
    std::size_t j = i + 2;
    while (j < buffer_.size() && static_cast<unsigned char>(buffer_[j]) >= 0x20 &&
           static_cast<unsigned char>(buffer_[j]) < 0x40)
      ++j;
    if (j >= buffer_.size()) {
      if (j - i > 64) {  // an endless sequence: drop it
        i = j;
        continue;
      }
      break;
    }
    const auto fb = static_cast<unsigned char>(buffer_[j]);
    if (fb >= 0x40 && fb < 0x7f) {
      Reply reply;
      if (auto e = decode_csi(std::string_view(buffer_).substr(i + 2, j - i - 2), static_cast<char>(fb), reply)) {
        // A terminal that answered the kitty query reports releases even for a plain
        // "CSI A" press (its event type 1 may be left out).
        if (kitty_supported_) e->kitty = true;
        out.push_back(*e);
      }
      if (reply.kind == Reply::device) device_answered_ = true;
      // Releases come only with "report event types"; an answer after DA1's is too late.
      if (reply.kind == Reply::kitty && !device_answered_) kitty_answered_ = true;
      if (reply.kind == Reply::kitty && (reply.kitty_flags & 2) != 0) kitty_supported_ = true;
    }
    i = j + 1;
  }
  buffer_.erase(0, i);
  return out;
}

std::vector<KeyEvent> KeyDecoder::flush() {
  std::vector<KeyEvent> out;
  if (buffer_ == "\x1b") out.push_back(KeyEvent{Key::escape});
  buffer_.clear();
  return out;
}

bool is_report(const KeyEvent& e) { return e.key == Key::mouse || e.key == Key::focus_in || e.key == Key::focus_out; }

std::optional<Direction> direction_of(const KeyEvent& e) {
  switch (e.key) {
    case Key::up: return Direction::up;
    case Key::down: return Direction::down;
    case Key::left: return Direction::left;
    case Key::right: return Direction::right;
    case Key::character:
      if (e.ch == 'w') return Direction::up;
      if (e.ch == 's') return Direction::down;
      if (e.ch == 'a') return Direction::left;
      if (e.ch == 'd') return Direction::right;
      if (e.ch == 'k') return Direction::up;  // vi keys
      if (e.ch == 'j') return Direction::down;
      if (e.ch == 'h') return Direction::left;
      if (e.ch == 'l') return Direction::right;
      return std::nullopt;
    default: return std::nullopt;
  }
}

namespace {
constexpr std::size_t idx(Direction d) { return static_cast<std::size_t>(d); }
constexpr Direction opposite(Direction d) {
  switch (d) {
    case Direction::up: return Direction::down;
    case Direction::down: return Direction::up;
    case Direction::left: return Direction::right;
    case Direction::right: return Direction::left;
  }
  return d;
}
constexpr std::uint64_t kForever = std::numeric_limits<std::uint64_t>::max();
}  // namespace

void HoldTracker::on_key(Direction d, const KeyEvent& e, std::uint64_t now_ms) {
  auto& until = until_ms_[idx(d)];
  if (e.action == KeyAction::release) {
    until = 0;
    return;
  }
  until_ms_[idx(opposite(d))] = 0;
  const bool repeating = e.action == KeyAction::repeat || held(d, now_ms) ||
                         (seen_[idx(d)] && now_ms - last_ms_[idx(d)] <= config_.repeat_gap_ms);
  seen_[idx(d)] = true;
  last_ms_[idx(d)] = now_ms;
  if (e.kitty) {
    until = kForever;  // a real release will come
  } else if (repeating) {
    until = std::max(until, now_ms + config_.repeat_hold_ms);
  } else {
    until = now_ms + config_.tap_ms;
  }
}

Steer steer_toward(double ball_x_u, double ball_y_u, double pointer_x_u, double pointer_y_u, double dead_u) {
  const auto axis = [dead_u](double from, double to) {
    if (!(to - from > dead_u) && !(from - to > dead_u)) return 0;  // NaN: no thrust
    return to > from ? 1 : -1;
  };
  return {axis(ball_x_u, pointer_x_u), axis(ball_y_u, pointer_y_u)};
}

bool HoldTracker::held(Direction d, std::uint64_t now_ms) const { return now_ms < until_ms_[idx(d)]; }

int HoldTracker::move_x(std::uint64_t now_ms) const {
  return (held(Direction::right, now_ms) ? 1 : 0) - (held(Direction::left, now_ms) ? 1 : 0);
}

int HoldTracker::move_y(std::uint64_t now_ms) const {
  return (held(Direction::up, now_ms) ? 1 : 0) - (held(Direction::down, now_ms) ? 1 : 0);
}

Action action_of(const KeyEvent& e, protocol::Phase phase) {
  if (e.key == Key::ctrl_c) return {ActionKind::quit};
  if (e.key == Key::mouse) return {ActionKind::pointer};
  if (e.key == Key::tab && e.action != KeyAction::release) return {ActionKind::follow};
  if (e.key == Key::character && e.ch == 't' && e.action == KeyAction::press) return {ActionKind::chat};
  if (e.action == KeyAction::release) {
    return direction_of(e) && phase == protocol::Phase::play ? Action{ActionKind::move} : Action{};
  }
  if (e.key == Key::character && e.ch == 'q') return {ActionKind::quit};
  if (phase == protocol::Phase::shop) {
    if (e.key == Key::enter) return {ActionKind::ready};
    if (e.key == Key::character && protocol::shop_index(e.ch) >= 0 && e.action == KeyAction::press)
      return {ActionKind::buy, e.ch};
    return {};
  }
  if (e.key == Key::enter && e.action == KeyAction::press) return {ActionKind::ready};
  if (e.key == Key::space) return {ActionKind::fire};
  if (direction_of(e)) return {ActionKind::move};
  return {};
}

}  // namespace fts::client
