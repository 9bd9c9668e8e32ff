// Pieces of the match step shared between its source files (not a public API).
#pragma once

#include "fts/sim/thrust.hpp"

#include <cmath>

#include <vector>

#include "fts/sim/match.hpp"

namespace fts::sim::detail {

// Adds a ball with the next id (ids only grow, so World stays sorted) and its body.
BallId add_ball(MatchState& s, Vec2 pos, Vec2 vel, double radius, double mass, const Body& body);
void remove_ball(MatchState& s, BallId id);

// Clears the platform and starts `level`: players at their spawn points, fresh enemies.
void start_level(MatchState& s, std::int64_t level, bool restart, std::vector<Event>& out);
// New match from level 1 for every present player (fresh economies).
void start_new_match(MatchState& s, std::vector<Event>& out);
// Puts the player's ball on a free spawn point, under spawn protection.
void respawn_player(MatchState& s, Player& p, std::vector<Event>& out);

// One tick of the playing phase (inputs sorted by player id).
void play_tick(MatchState& s, const std::vector<PlayerTick>& inputs, std::vector<Event>& out);
// Enemy behaviour: goals and thrust for every enemy.
void steer_enemies(MatchState& s);

// Thrust on one axis: dir in {-1, 0, +1}; applied only while the component's magnitude
// is below vmax, as the original did (GAME_RULES.md "Balls"). So a ball knocked faster
// than vmax cannot brake until friction brings it back under vmax.
using sim::thrust_axis;  // fts/sim/thrust.hpp: one rule for the match and the prediction

}  // namespace fts::sim::detail
