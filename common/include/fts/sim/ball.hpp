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
  // Arbitrary mass unit. +inf: immovable for the tick (the match's spawn protection,
  // set only around a step): collisions never move it, others reflect off it.
  double mass = 1.0;
  // Axes thrust this tick (kThrustX | kThrustY), set by the game before the step: the
  // friction cut-off spares them so a ball can start moving at any tick rate. Not state:
  // step() clears it, as Box2D clears a body's force after each step.
  std::uint8_t thrust_axes = 0;
};

constexpr std::uint8_t kThrustX = 1;
constexpr std::uint8_t kThrustY = 2;

}  // namespace fts::sim
