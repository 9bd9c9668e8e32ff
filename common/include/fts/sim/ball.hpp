// A ball of the physics world: the only body type there is.
#pragma once

#include <cstdint>

#include "fts/sim/id.hpp"
#include "fts/sim/vec2.hpp"

namespace fts::sim {

struct Ball {
  BallId id = 0;
  Vec2 pos;        // u
  Vec2 vel;        // u/s
  double radius = 1.0;  // u
  double mass = 1.0;    // arbitrary mass unit
};

}  // namespace fts::sim
