// The continuous model's conservative tests (internal to fts_common; see
// step_continuous.cpp): whether a ball can reach an edge or leave its skin within a
// time, and for how many ticks two balls certainly stay apart. Each errs only toward
// "maybe": a wrong "maybe" costs a prediction, never a result. And the small pieces of
// the solve that need none of its state (a path's box, the push-apart of a pile).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include <algorithm>
#include <utility>
#include <vector>

#include "fts/sim/ball.hpp"
#include "fts/sim/collide.hpp"
#include "fts/sim/step_buffers.hpp"
#include "fts/sim/physics.hpp"
#include "lanes.hpp"

namespace fts::sim::detail {

// A listed pair whose balls keep their lines is predicted again after at most this many
// ticks, however far apart it was (bounds the rounding drift the margins must cover).
constexpr std::uint32_t kMaxSkip = 16;

// The arena's edges, as clear_of_edges reads them.
struct Edges {
  bool walls;
  double width, height;
};
// Whether ball b, within `time` at its speed, certainly reaches no edge: |vx| + |vy|
// bounds the speed from above, and the four tests run without branches, x and y in the
// two lanes (almost every ball passes all four).
// B: a Ball or its working copy (SolverBall), here and below.
template <class B>
[[gnu::always_inline]] inline bool clear_of_edges(const B& b, double time, const Edges& e) {
  const double travel = (std::fabs(b.vel.x) + std::fabs(b.vel.y)) * time;
  const double inset = e.walls ? b.radius : 0.0;
  const D2 p = lanes(b.pos), t = {travel, travel};
  const D2 lo = {inset, inset}, hi = {e.width - inset, e.height - inset};
  const auto clear = ((p - t) > lo) & ((p + t) < hi);
  return (clear[0] & clear[1]) != 0;
}

// Whether a ball at pos moving at vel for `time` stays within sqrt(h2) of origin (a
// straight path: both ends suffice). Callers pass 0.99 of half_skin, 1 % short of the
// box, so that rounding cannot put a ball that passes outside it.
[[gnu::always_inline]] inline bool stays_within(const Vec2& pos, const Vec2& vel, double time, const Vec2& origin,
                                                double h2) {
  const D2 d = lanes(pos) - lanes(origin);
  const D2 e = d + lanes(vel) * D2{time, time};
  const D2 dd = d * d, ee = e * e;
  return (dd[0] + dd[1] <= h2) & (ee[0] + ee[1] <= h2);
}

// Whole ticks of dt, from the start of this one (every clock 0), in which balls a and b
// on their present lines certainly do not touch: 0 (predict now) .. kMaxSkip. For
// t >= 0, |d + w t|^2 >= |d|^2 + 2 (d.w) t, which stays above reach^2 until
// t = c / (-2 d.w). The reach is widened by 1e-6 of itself and by `slack` (1e-12 of the
// arena), far above the rounding here and the drift of positions re-based every tick
// for kMaxSkip ticks, so a skipped tick is one whose prediction would have found
// nothing.
template <class B>
[[gnu::always_inline]] inline std::uint32_t ticks_kept_apart(const B& a, const B& b, double slack, double dt) {
  const Vec2 d = b.pos - a.pos;
  const double reach = (a.radius + b.radius) * (1.0 + 1e-6) + slack;
  const double c = length_sq(d) - reach * reach;
  if (!(c > 0.0)) return 0;
  const double approach = dot(d, b.vel - a.vel);
  if (approach >= 0.0) return kMaxSkip;
  const double ticks = c / (-2.0 * approach * dt);
  if (!(ticks >= 1.0)) return 0;  // also NaN
  return ticks >= static_cast<double>(kMaxSkip) ? kMaxSkip : static_cast<std::uint32_t>(ticks);
}

// The box around ball b's path from its clock to the end of the tick (dt), widened by
// its radius; margin_scale > 0 widens it a little more (an escaped ball's box, which
// must hold its path until its next event whatever the rounding).
[[gnu::always_inline]] inline Box box_of_path(const SolverBall& b, double dt, double margin_scale) {
  const Vec2 end = b.pos + b.vel * (dt - b.t);
  // |vx| + |vy| bounds the speed from above without a square root.
  const double speed_margin = margin_scale * (std::fabs(b.vel.x) + std::fabs(b.vel.y)) * (dt - b.t);
  const double m = b.radius * (1.0 + 0.05 * margin_scale) + speed_margin;
  return {std::min(b.pos.x, end.x) - m, std::min(b.pos.y, end.y) - m, std::max(b.pos.x, end.x) + m,
          std::max(b.pos.y, end.y) + m};
}

// An edge event's code in place of the second ball's index.
constexpr std::uint32_t kWallX = 0xffffff00u;
constexpr std::uint32_t kWallY = 0xffffff01u;
constexpr std::uint32_t kFall = 0xffffff02u;

struct EdgeHit {
  double after;        // time from the ball's clock; infinity: none
  std::uint32_t edge;  // kWallX, kWallY or kFall
};
// The first edge ball b reaches on its line: a wall (walls), or an open edge it falls
// from — at once when it is already off the platform (pushed out by a separation),
// whatever its velocity.
inline EdgeHit first_edge(const SolverBall& b, const Arena& a) {
  EdgeHit hit{std::numeric_limits<double>::infinity(), kWallX};
  auto axis = [&](double p, double v, double lo, double hi, std::uint32_t edge) {
    double t = hit.after;
    if (v < 0.0) t = p <= lo ? 0.0 : (lo - p) / v;
    else if (v > 0.0) t = p >= hi ? 0.0 : (hi - p) / v;
    if (t < hit.after) hit = {t, edge};
  };
  if (a.boundary == Boundary::walls) {
    axis(b.pos.x, b.vel.x, b.radius, a.width_u - b.radius, kWallX);
    axis(b.pos.y, b.vel.y, b.radius, a.height_u - b.radius, kWallY);
  } else if (!(b.pos.x >= 0.0 && b.pos.x <= a.width_u && b.pos.y >= 0.0 && b.pos.y <= a.height_u)) {
    hit = {0.0, kFall};
  } else {
    axis(b.pos.x, b.vel.x, 0.0, a.width_u, kFall);
    axis(b.pos.y, b.vel.y, 0.0, a.height_u, kFall);
  }
  return hit;
}

// Pushes apart each listed pair of balls (in the list's order) that still overlaps.
inline void separate_pairs(std::vector<Ball>& balls,
                           const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  for (auto [i, j] : pairs) {
    Ball& a = balls[i];
    Ball& b = balls[j];
    const double reach = a.radius + b.radius;
    const Vec2 d = b.pos - a.pos;
    const double dist = length(d);
    if (dist < reach) separate(a, b, unit_normal(d, dist), reach - dist);
  }
}

// Every ball's centre into a walled arena (at its middle where the ball is wider).
inline void clamp_into_walls(std::vector<Ball>& balls, const Arena& a) {
  for (Ball& b : balls) {
    const double half_w = a.width_u * 0.5, half_h = a.height_u * 0.5;
    b.pos.x = std::clamp(b.pos.x, std::min(b.radius, half_w), std::max(a.width_u - b.radius, half_w));
    b.pos.y = std::clamp(b.pos.y, std::min(b.radius, half_h), std::max(a.height_u - b.radius, half_h));
  }
}

}  // namespace fts::sim::detail
