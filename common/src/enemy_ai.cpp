// Enemy behaviour: wanderers steer toward a goal point drawn in a box around the
// platform centre (a coordinate is redrawn once reached within 3 u); the chaser's goal
// is the nearest living player. Level 1's enemy stays still.
#include <cmath>
#include <limits>

#include "match_internal.hpp"

namespace fts::sim::detail {
namespace {

int toward(double from, double to) { return to > from ? 1 : (to < from ? -1 : 0); }

// Position of the living player ball nearest to `pos` (ties: lowest ball id).
const Ball* nearest_player(const MatchState& s, Vec2 pos) {
  const Ball* best = nullptr;
  double best_d = std::numeric_limits<double>::infinity();
  for (const Player& p : s.players) {
    if (!p.ball) continue;
    const Ball* b = find_ball(s.world, p.ball);
    if (!b) continue;
    const double d = length_sq(b->pos - pos);
    if (d < best_d || (d == best_d && best && b->id < best->id)) {
      best = b;
      best_d = d;
    }
  }
  return best;
}

}  // namespace

void steer_enemies(MatchState& s) {
  const double dt = s.step_k.dt_s;
  const Vec2 half = goal_half_size(s.level, s.cfg);
  const Vec2 centre{s.cfg.arena_width_u * 0.5, s.cfg.arena_height_u * 0.5};
  // The balls and the bodies are both in id order: walked together (a binary search of
  // the room's cold bodies for each ball was most of this function's time at 256 clients).
  auto at = s.bodies.begin();
  for (Ball& b : s.world.balls) {
    while (at != s.bodies.end() && at->first < b.id) ++at;
    if (at == s.bodies.end() || at->first != b.id) at = s.bodies.emplace(b.id, Body{}).first;  // as [] did
    Body& body = at->second;
    if (body.kind != BodyKind::enemy || body.spec.role == EnemyRole::still) continue;
    const Ball* target = body.spec.role == EnemyRole::chaser ? nearest_player(s, b.pos) : nullptr;
    if (target) {
      body.goal = target->pos;
    } else {
      if (std::fabs(body.goal.x - b.pos.x) <= s.cfg.goal_reach_u)
        body.goal.x = s.rng.uniform(centre.x - half.x, centre.x + half.x);
      if (std::fabs(body.goal.y - b.pos.y) <= s.cfg.goal_reach_u)
        body.goal.y = s.rng.uniform(centre.y - half.y, centre.y + half.y);
    }
    const int dx = toward(b.pos.x, body.goal.x), dy = toward(b.pos.y, body.goal.y);
    thrust_axis(b.vel.x, dx, body.spec.accel_u_per_s2, body.spec.vmax_u_per_s, dt);
    thrust_axis(b.vel.y, dy, body.spec.accel_u_per_s2, body.spec.vmax_u_per_s, dt);
    b.thrust_axes = static_cast<std::uint8_t>((dx != 0 ? kThrustX : 0) | (dy != 0 ? kThrustY : 0));
  }
}

}  // namespace fts::sim::detail
