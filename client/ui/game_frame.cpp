#include "ui/game_frame.hpp"

#include <cmath>

#include "ui/render.hpp"

namespace fts::client {

Screen game_frame(const SnapshotBuffer& buffer, NetTiming& net, ViewState& view, TerminalSize size,
                  std::uint64_t now, std::optional<int> fixed_delay_ms) {
  const protocol::Snapshot* newest = buffer.newest();
  if (!newest) {
    protocol::Snapshot empty;
    return render(empty, empty, 0, size, view);
  }
  if (newest->phase != protocol::Phase::play) return render(*newest, *newest, 0, size, view);
  // Remote balls: behind the server clock by the jitter buffer's delay.
  const double render_tick = net.remote_tick(now, fixed_delay_ms);
  view.delay_ms = static_cast<int>(std::lround(net.remote_delay_ms()));
  net.frame_drawn(render_tick > static_cast<double>(newest->tick) + 1e-9, now);
  const Frame f = buffer.sample(render_tick);
  // The own ball: predicted, at the tick its inputs act (else the snapshots').
  if (const auto own = net.predicting() ? net.own_ball(now) : std::nullopt) {
    net.drawn(own->vx, own->vy, now);
    protocol::Snapshot a = *f.a, b = *f.b;
    place_own_ball(a, view.my_player_id, *own);
    place_own_ball(b, view.my_player_id, *own);
    const auto near = net.near_balls();  // the balls it may hit, in its time (issue 37)
    place_near_balls(a, near, *own);
    place_near_balls(b, near, *own);
    return render(a, b, f.alpha, size, view);
  }
  for (const auto& ball : f.b->balls)  // what the screen shows of our ball's motion
    if (ball.kind == protocol::BallKind::player && ball.owner == view.my_player_id) net.drawn(ball.vx, ball.vy, now);
  return render(*f.a, *f.b, f.alpha, size, view);
}

}  // namespace fts::client
