// A built-in bot: a deterministic controller that reads the match state and fills the
// same PlayerTick a human's client would. In play it pushes the nearest enemy toward
// that enemy's nearest edge while keeping itself on the platform; in the shop it buys
// what it can afford (a life when low, the bank, acceleration, speed, mass) and readies.
#pragma once

#include "fts/sim/match.hpp"

namespace fts::sim {

PlayerTick bot_tick(const MatchState& s, PlayerId id);

}  // namespace fts::sim
