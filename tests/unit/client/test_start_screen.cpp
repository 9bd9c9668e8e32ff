// The start screen's choices (issue 13): typed lines to the hello's join fields.
#include <catch2/catch.hpp>

#include "ui/start_screen.hpp"

using namespace fts::client;

TEST_CASE("Start screen: a typed line picks quick, create, join CODE or spectate CODE", "[client][rooms]") {
  CHECK(std::get<RoomChoice>(parse_start_choice("")) == RoomChoice{"quick", ""});
  CHECK(std::get<RoomChoice>(parse_start_choice(" 1 ")) == RoomChoice{"quick", ""});
  CHECK(std::get<RoomChoice>(parse_start_choice("2")) == RoomChoice{"create", ""});
  CHECK(std::get<RoomChoice>(parse_start_choice("3 kxbqt")) == RoomChoice{"join", "KXBQT"});
  CHECK(std::get<RoomChoice>(parse_start_choice("s KXBQT")) == RoomChoice{"spectate", "KXBQT"});
  // Mistakes say what is wrong.
  CHECK(std::get<std::string>(parse_start_choice("3")).find("code") != std::string::npos);
  CHECK(std::get<std::string>(parse_start_choice("3 HELLO")).find("not a room code") != std::string::npos);
  CHECK(std::get<std::string>(parse_start_choice("3 AB")).find("not a room code") != std::string::npos);
  CHECK(std::holds_alternative<std::string>(parse_start_choice("9")));
  CHECK(room_label("KXBQT", false) == "Room KXBQT");
  CHECK(room_label("KXBQT", true) == "Watching KXBQT");
  CHECK(room_label("", false).empty());
}
