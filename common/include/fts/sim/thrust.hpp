// Thrust for one tick (GAME_RULES.md "Movement"; README "Where the rules left room"): on
// each axis the ball gains a * dt toward `dir` while that velocity component is below
// vmax; the thrusted axes are marked, so that friction's cut-off spares them. The match
// (players and enemies) and the client's prediction apply thrust through this one header.
#pragma once

#include <cmath>
#include <cstdint>

#include "fts/sim/ball.hpp"

namespace fts::sim {

inline void thrust_axis(double& v, int dir, double accel, double vmax, double dt) {
  if (dir != 0 && std::fabs(v) < vmax) v += dir * accel * dt;
}

// A player's thrust on its ball: dx, dy in -1..1.
inline void apply_thrust(Ball& b, int dx, int dy, double accel, double vmax, double dt) {
  thrust_axis(b.vel.x, dx, accel, vmax, dt);
  thrust_axis(b.vel.y, dy, accel, vmax, dt);
  b.thrust_axes = static_cast<std::uint8_t>((dx != 0 ? kThrustX : 0) | (dy != 0 ? kThrustY : 0));
}

}  // namespace fts::sim
