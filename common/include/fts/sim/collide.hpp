// Pairwise collision response; shared by the models and tested against each other.
#pragma once

#include "fts/sim/ball.hpp"

namespace fts::sim {

// The seed's rotated-axes formulas (atan2/cos/sin), applied unconditionally.
void respond_seed(Ball& b1, Ball& b2);
// The seed's push-apart: b1 moves one unit per axis away from b2 until they no longer
// overlap. A zero difference on an axis moves nothing on it; both zero moves b1 along +x.
// Bounded: after max_iterations any remaining overlap is removed in one jump.
// Returns the number of unit steps taken.
int push_apart_seed(Ball& b1, const Ball& b2, int max_iterations = 4096);

// Unit contact normal from a to b; for coincident centres a fixed deterministic +x.
Vec2 contact_normal(const Ball& a, const Ball& b);
// Elastic impulse along unit normal n (a to b) if the pair approaches. Returns true
// when an impulse was applied.
bool respond_elastic(Ball& a, Ball& b, Vec2 n);
// Removes the overlap along n, each ball moving in proportion to the other's mass.
void separate(Ball& a, Ball& b, Vec2 n, double overlap);

}  // namespace fts::sim
