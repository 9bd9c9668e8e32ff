// Drawing is a pure function: two snapshots, how far between them, the terminal size and
// the view state give the screen. The platform keeps its aspect ratio; every ball is a
// disc of cells with its mass written in it; the HUD, the shop and a help line are text.
#pragma once

#include "fts/protocol/snapshot.hpp"
#include "ui/layout.hpp"
#include "ui/screen.hpp"
#include "ui/view.hpp"

namespace fts::client {

// Fill characters: your ball, other players, enemies, rockets, the platform.
inline constexpr char kMyBallChar = '@';
inline constexpr char kPlayerBallChar = 'O';
inline constexpr char kEnemyBallChar = '#';
inline constexpr char kRocketChar = '*';
inline constexpr char kPlatformChar = '.';
// The own ball's exhaust (behind it while it thrusts): sideways, up or down, diagonal.
inline constexpr char kExhaustSide = '=';
inline constexpr char kExhaustUpDown = '"';
inline constexpr char kExhaustDiagonal = '%';

// A purchase's result ("Cannot buy: ...") stays this long in the shop, then goes: a
// stale refusal must not read as the answer to the next key (issue 37).
inline constexpr std::uint64_t kShopResultShowMs = 6000;

// A name written on the field is cut to this many characters.
inline constexpr int kNameOnFieldChars = 10;

// The platform's place for a terminal size (inside a one-cell frame; see panel.hpp).
Viewport arena_viewport(TerminalSize size, const ViewState& view, const protocol::Snapshot& snap = {});

Screen render(const protocol::Snapshot& a, const protocol::Snapshot& b, double alpha,
              TerminalSize size, const ViewState& view);

}  // namespace fts::client
