#include "bot/script.hpp"

#include <cmath>
#include <sstream>

#include "fts/protocol/codes.hpp"

namespace fts::bot {
namespace {

// A finite number within +-1e9 (ticks, seconds, expected values): anything else in a
// script is a mistake, and larger values would overflow the tick and time arithmetic.
bool to_number(const std::string& s, double& out) {
  try {
    std::size_t used = 0;
    out = std::stod(s, &used);
    return used == s.size() && std::isfinite(out) && std::fabs(out) <= 1e9;
  } catch (...) {
    return false;
  }
}

bool is_one_of(const std::string& w, std::initializer_list<const char*> words) {
  for (const char* x : words)
    if (w == x) return true;
  return false;
}

}  // namespace

bool compare(double lhs, const std::string& cmp, double rhs) {
  if (cmp == "==") return lhs == rhs;
  if (cmp == "!=") return lhs != rhs;
  if (cmp == ">=") return lhs >= rhs;
  if (cmp == "<=") return lhs <= rhs;
  if (cmp == ">") return lhs > rhs;
  if (cmp == "<") return lhs < rhs;
  return false;
}

std::variant<std::vector<Step>, std::string> parse_script(const std::string& text) {
  std::vector<Step> steps;
  std::istringstream in(text);
  std::string raw;
  for (int no = 1; std::getline(in, raw); ++no) {
    const std::string line = raw.substr(0, raw.find('#'));
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (w.empty()) continue;
    Step s;
    s.line = no;
    s.text = line;
    auto err = [&](const std::string& m) { return "line " + std::to_string(no) + ": " + m + ": " + raw; };
    auto need = [&](std::size_t n) { return w.size() == n; };
    const std::string& k = w[0];
    if (k == "wait") {
      if (!need(2) && !(need(3) && w[1] == "ticks")) return err("wait takes one word (or 'ticks N')");
      if (w[1] == "ticks") {
        s.op = Step::Op::wait_ticks;
        if (!to_number(w[2], s.number) || s.number < 0) return err("wait ticks needs a number");
      } else if (is_one_of(w[1], {"connected", "level_started", "level_complete", "game_over", "enemy_fell",
                                  "player_fell", "purchase"})) {
        s.op = Step::Op::wait_event;
        s.word = w[1];
      } else if (is_one_of(w[1], {"lobby", "play", "shop", "over"})) {
        s.op = Step::Op::wait_phase;
        s.word = w[1];
      } else {
        return err("unknown event or phase '" + w[1] + "'");
      }
    } else if (k == "timeout") {
      s.op = Step::Op::set_timeout;
      if (!need(2) || !to_number(w[1], s.number) || s.number <= 0) return err("timeout needs seconds > 0");
    } else if (k == "move") {
      s.op = Step::Op::move;
      if (!need(3) || !is_one_of(w[1], {"left", "right", "up", "down", "none"}) || !to_number(w[2], s.number) ||
          s.number < 0)
        return err("move takes a direction (left right up down none) and ticks");
      s.word = w[1];
    } else if (k == "hunt") {
      s.op = Step::Op::hunt;
      s.number = -1;  // no count: hunt through the following steps, until a move
      if (need(2) && (!to_number(w[1], s.number) || s.number < 0)) return err("hunt takes ticks (or nothing)");
      if (w.size() > 2) return err("hunt takes ticks (or nothing)");
    } else if (k == "fire" && need(1)) {
      s.op = Step::Op::fire;
    } else if (k == "buy") {
      s.op = Step::Op::buy;
      if (!need(2)) return err("buy takes an item");
      static const char* items[][2] = {{"mass", "m"}, {"speed", "s"}, {"accel", "a"}, {"rockets", "r"},
                                       {"life", "l"}, {"multiplier", "x"}, {"bank", "b"}};
      for (auto& it : items)
        if (w[1] == it[0] || w[1] == it[1]) s.word = it[1];
      if (s.word.empty()) return err("unknown item '" + w[1] + "'");
    } else if (k == "ready" && need(1)) {
      s.op = Step::Op::ready;
    } else if (k == "play_again" && need(1)) {
      s.op = Step::Op::play_again;
    } else if (k == "expect") {
      if (w.size() >= 3 && w[1] == "room") {
        s.op = Step::Op::expect_room;
        if (need(4) && w[2] == "refused") {
          // The code is the wire's (codes.hpp): a misspelt one would never be met.
          if (!protocol::error_code_of(w[3])) return err("expect room refused: '" + w[3] + "' is no error code (PROTOCOL.md 4.4)");
          s.word = "refused";
          s.cmp = w[3];
        } else if (need(3) && w[2] != "refused") {
          s.word = w[2];
        } else {
          return err("expect room takes a code, 'any', or 'refused REASON'");
        }
      } else if (need(3) && w[1] == "result" && is_one_of(w[2], {"ok", "refused"})) {
        s.op = Step::Op::expect_result;
        s.word = w[2];
      } else if (need(4) && is_one_of(w[1], {"coins", "lives", "level", "mass", "tick", "purchases"}) &&
                 is_one_of(w[2], {"==", "!=", ">=", "<=", ">", "<"}) && to_number(w[3], s.number)) {
        s.op = Step::Op::expect_field;
        s.word = w[1];
        s.cmp = w[2];
      } else {
        return err("expect takes 'FIELD OP NUMBER' or 'result ok|refused'");
      }
    } else if (k == "disconnect" && need(1)) {
      s.op = Step::Op::disconnect;
    } else if (k == "reconnect" && need(1)) {
      s.op = Step::Op::reconnect;
    } else {
      return err("unknown step '" + k + "'");
    }
    steps.push_back(std::move(s));
  }
  return steps;
}

}  // namespace fts::bot
