// The start screen: how a player picks a room (quick play, create, join by code,
// spectate), either by a flag (--quick, --create, --join CODE, --spectate CODE) or by a
// typed choice at the prompt. Pure: the caller prints the menu and reads the lines.
#pragma once

#include <optional>
#include <string>
#include <variant>

namespace fts::client {

// What the hello asks for (Hello::join, Hello::room).
struct RoomChoice {
  std::string join = "quick";  // quick, create, join, spectate
  std::string room;            // the code for join and spectate
  bool operator==(const RoomChoice&) const = default;
};

// The menu shown before connecting, its lines wrapped to `cols` (the terminal's width).
std::string start_menu_text(int cols = 80);

// One typed line -> the choice, or a sentence saying what is wrong (ask again).
// "1" or "q" or "" (Enter): quick play; "2" or "c": create; "3 CODE" or "j CODE": join;
// "4 CODE" or "s CODE": spectate. Codes are 5 letters, any case.
std::variant<RoomChoice, std::string> parse_start_choice(const std::string& line);

// The HUD's room field: "Room ABCDE" (or "Watching ABCDE"); "" without a room.
std::string room_label(const std::string& code, bool spectator);

}  // namespace fts::client
