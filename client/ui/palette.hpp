// Each player's colour, the same on every client: picked by player id from one table, so
// "the green one" is the same player for everybody. Enemies keep red and the platform gray.
#pragma once

#include <array>
#include <cstdint>

#include "ui/screen.hpp"

namespace fts::client {

inline constexpr std::array<Color, 8> kPlayerColors = {
    Color::yellow, Color::cyan,         Color::green,       Color::magenta,
    Color::blue,   Color::bright_green, Color::bright_cyan, Color::white,
};

inline Color player_color(std::uint32_t player_id) {
  return player_id == 0 ? Color::white : kPlayerColors[(player_id - 1) % kPlayerColors.size()];
}

inline Style player_style(std::uint32_t player_id, bool bold = true) {
  return Style{player_color(player_id), Color::none, bold, false, false};
}

}  // namespace fts::client
