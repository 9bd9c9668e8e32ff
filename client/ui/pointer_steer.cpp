#include "ui/pointer_steer.hpp"

#include <algorithm>
#include <cmath>

namespace fts::client {

std::optional<SteerBall> steer_ball(const protocol::Snapshot& s, std::uint32_t me) {
  const protocol::PlayerState* player = nullptr;
  for (const auto& p : s.players)
    if (p.id == me) player = &p;
  if (player == nullptr) return std::nullopt;
  for (const auto& b : s.balls)
    if (b.kind == protocol::BallKind::player && b.owner == me)
      return SteerBall{b.id, b.x, b.y, b.vx, b.vy, b.radius, player->accel_u_per_s2, player->vmax_u_per_s};
  return std::nullopt;
}

void PointerSteering::aim(double x_u, double y_u, bool on_platform) {
  if (!on_platform || !std::isfinite(x_u) || !std::isfinite(y_u)) {
    if (active_) why_ = "left the platform";
    active_ = false;
    return;
  }
  if (!active_) ball_id_ = 0;  // bound to the ball the next update sees
  active_ = true;
  why_ = "";
  aim_x_ = x_u;
  aim_y_ = y_u;
}

// One axis: toward the target until the braking distance (with slack) reaches what is
// left, then against the motion; at the target, against any motion faster than "still".
int PointerSteering::axis(double at, double v, double target, double accel) const {
  const double left = target - at;
  const int dir = left > 0 ? 1 : -1;
  if (std::fabs(left) <= k_.arrive_u) return std::fabs(v) > k_.still_u_per_s ? (v > 0 ? -1 : 1) : 0;
  const double toward = v * dir;  // speed toward the target (negative: away)
  if (toward > 0 && toward * toward / (2 * accel) * k_.brake_slack >= std::fabs(left)) return -dir;
  return dir;
}

Steer PointerSteering::update(const SteerBall* ball, double width_u, double height_u, double delay_s) {
  if (!active_) return {};
  if (ball == nullptr || (ball_id_ != 0 && ball->id != ball_id_)) {
    active_ = false;
    why_ = "new ball";
    return {};
  }
  ball_id_ = ball->id;
  // The aim a radius and a margin inside the platform: the centre leaving it is a fall.
  const double inset = ball->radius + k_.edge_margin_u;
  const double tx = std::clamp(aim_x_, std::min(inset, width_u / 2), std::max(width_u - inset, width_u / 2));
  const double ty = std::clamp(aim_y_, std::min(inset, height_u / 2), std::max(height_u - inset, height_u / 2));
  // Where the ball is when this input acts.
  const double delay = std::clamp(delay_s, 0.0, 0.5);
  const double x = ball->x + ball->vx * delay, y = ball->y + ball->vy * delay;
  if (std::fabs(tx - x) <= k_.arrive_u && std::fabs(ty - y) <= k_.arrive_u && std::fabs(ball->vx) <= k_.still_u_per_s &&
      std::fabs(ball->vy) <= k_.still_u_per_s) {
    active_ = false;
    why_ = "arrived";
    return {};
  }
  const double a = ball->accel > 1e-6 ? ball->accel : 1e-6;
  return {axis(x, ball->vx, tx, a), axis(y, ball->vy, ty, a)};
}

}  // namespace fts::client
