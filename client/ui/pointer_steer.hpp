// Mouse steering that arrives (Reynolds' "arrival" with the game's per-axis thrust): the
// ball goes to the pointer and stops there, and never thrusts itself off the platform.
//
// The old rule thrust toward the pointer until the ball was within a cell of it and then
// let go: a ball at vmax coasts about 200 u on the game's friction (0.991 per 10 ms), so it
// overshot, and near an edge it coasted off; the thrust also outlived a respawn (issue 26).
// Here, per axis, the ball brakes once its braking distance (v^2 / 2a, plus the distance it
// covers in the input's delay) reaches what is left; the aim is kept a ball's radius and a
// margin inside the platform; and steering ends by itself:
//   - when the ball is at the aim and slow (arrived),
//   - when the pointer leaves the platform, the window loses focus, or a key steers,
//   - when the own ball is gone or replaced (a fall, a respawn, a new level).
// Pure: the caller passes the ball as the newest snapshot shows it and the delay.
#pragma once

#include <cstdint>
#include <optional>

#include "fts/protocol/snapshot.hpp"
#include "term/keys.hpp"

namespace fts::client {

struct SteerBall {
  std::uint32_t id = 0;  // the ball's id: another id is another life (steering ends)
  double x = 0, y = 0, vx = 0, vy = 0, radius = 16;  // u, u/s
  double accel = 200, vmax = 170;                    // the player's a (u/s^2) and vmax (u/s)
};

// Our ball and our player's a and vmax in a snapshot (nothing: no ball on the platform).
std::optional<SteerBall> steer_ball(const protocol::Snapshot& s, std::uint32_t me);

struct SteerTuning {
  double edge_margin_u = 8;     // the aim stays this far inside the platform beyond the radius
  double arrive_u = 6;          // at the aim within this on both axes...
  double still_u_per_s = 12;    // ...and this slow on both: arrived, steering ends
  double brake_slack = 1.25;    // the braking distance is counted this much longer (friction
                                // helps; the snapshot's position is a little old)
};

class PointerSteering {
 public:
  explicit PointerSteering(SteerTuning tuning = {}) : k_(tuning) {}

  // The pointer moved or was pressed at arena point (x, y); `on_platform`: inside the
  // platform's rectangle. Off the platform, steering ends.
  void aim(double x_u, double y_u, bool on_platform);
  // Steering ends (focus lost, a steering key, the phase left play).
  void stop() { active_ = false; }
  bool active() const { return active_; }
  // Why it last ended ("" while active or never started): "arrived", "left the platform",
  // "stopped", "new ball".
  const char* ended_because() const { return why_; }

  // The thrust this frame for the own ball as the newest snapshot shows it (nullptr: no
  // ball on the platform), on a platform of width x height, with `delay_s` between that
  // snapshot's state and the time this input acts (snapshot age plus half a round trip).
  Steer update(const SteerBall* ball, double width_u, double height_u, double delay_s);

 private:
  int axis(double at, double v, double target, double accel) const;
  SteerTuning k_;
  bool active_ = false;
  const char* why_ = "";
  double aim_x_ = 0, aim_y_ = 0;
  std::uint32_t ball_id_ = 0;  // the ball steering started with (0: not seen yet)
};

}  // namespace fts::client
