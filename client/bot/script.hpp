// The bot script language: one step per line, '#' starts a comment.
//
//   wait connected | wait level_started | wait level_complete | wait shop | wait play
//   wait game_over | wait ticks N          wait for an event or phase (deadline: timeout)
//   timeout SECONDS                         deadline of the following waits (default 60)
//   move left|right|up|down|none TICKS      hold a thrust for TICKS server ticks
//   hunt [TICKS]                            play as the hunter for TICKS ticks (no TICKS:
//                                           through the following steps, until a move)
//   fire                                    fire a rocket (this tick)
//   buy ITEM                                ITEM: mass speed accel rockets life multiplier bank
//                                           (or m s a r l x b); waits for the result
//   ready | play_again                      send the command; waits for the result
//   expect FIELD OP NUMBER                  FIELD: coins lives level mass tick purchases
//                                           OP: == != >= <= > <
//   expect result ok|refused                the last command's result
//   expect room CODE|any                    welcomed into room CODE (any: some room)
//   expect room refused REASON              the join is refused with REASON (room_full,
//                                           no_such_room, server_full): the bot succeeds
//   disconnect | reconnect                  clean bye; new handshake with the session token
//
// A failed expect, a refused connection or a missed deadline ends the bot with a message.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace fts::bot {

struct Step {
  enum class Op { wait_event, wait_phase, wait_ticks, set_timeout, move, hunt, fire, buy, ready, play_again,
                  expect_field, expect_result, expect_room, disconnect, reconnect };
  Op op = Op::wait_ticks;
  std::string word;     // event, phase, direction, item, field, "ok"/"refused", comparison
  std::string cmp;      // expect: == != >= <= > <
  double number = 0;    // ticks, seconds, expected value
  int line = 0;
  std::string text;     // the line as written, for messages
};

// Either the steps or "line N: message".
std::variant<std::vector<Step>, std::string> parse_script(const std::string& text);

bool compare(double lhs, const std::string& cmp, double rhs);

}  // namespace fts::bot
