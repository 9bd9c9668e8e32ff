#include "net/net_timing.hpp"

#include <algorithm>
#include <cmath>

namespace fts::client {

void NetTiming::on_welcome(const protocol::Welcome& w) {
  tick_rate_hz_ = w.tick_rate_hz();
  ticks_per_snapshot_ = w.snapshot_rate_hz > 0 ? tick_rate_hz_ / w.snapshot_rate_hz : 5;
  jitter_ = JitterBuffer();
  jitter_.set_rates(tick_rate_hz_, ticks_per_snapshot_);
  lead_ = LeadClock();
  loss_ = LossMeter();
  shown_tick_ = 0;
  delay_ms_ = 0;
  last_arrival_ms_ = 0;
  // The prediction steps the match's physics as the server configured it: everything the
  // welcome carries of its configuration (platform, tick rate, model, sub-steps, friction).
  predictor_ = OwnBallPredictor(w.match, tuning_);
}

void NetTiming::on_snapshot(const protocol::Snapshot& s, std::uint32_t me, std::uint64_t now_ms) {
  if (last_arrival_ms_ != 0 && now_ms > last_arrival_ms_)
    longest_gap_ms_ = std::max(longest_gap_ms_, now_ms - last_arrival_ms_);
  last_arrival_ms_ = now_ms;
  jitter_.on_snapshot(s.tick, now_ms);
  jitter_max_ms_ = std::max(jitter_max_ms_, jitter_.jitter_ms());
  loss_.on_snapshot(s.tick, ticks_per_snapshot_);
  if (predict_) predictor_.on_snapshot(s, me, shown_tick_, now_ms);
}

double NetTiming::own_tick(std::uint64_t now_ms, double rtt_ms) {
  shown_tick_ = lead_.predicted(jitter_.clock().tick_at(now_ms), rtt_ms, jitter_.jitter_ms(), tick_rate_hz_, now_ms);
  return shown_tick_;
}

void NetTiming::sent(const protocol::InputFrame& f) {
  if (f.tick != 0) predictor_.input(f.tick, f.move_x, f.move_y);
}

double NetTiming::remote_tick(std::uint64_t now_ms, std::optional<int> fixed_ms) {
  delay_ms_ = fixed_ms ? *fixed_ms : jitter_.delay_ms(now_ms);
  return jitter_.clock().tick_at(now_ms) - delay_ms_ * tick_rate_hz_ / 1000.0;
}

void NetTiming::frame_drawn(bool stalled, std::uint64_t now_ms) {
  ++frames_;
  stalls_.frame(stalled, now_ms);
}

void NetTiming::drawn(double vx, double vy, std::uint64_t now_ms) {
  drawn_vx_ = vx;
  drawn_vy_ = vy;
  response_.drawn(vx, vy, now_ms);
}

std::string NetTiming::stats_json(std::uint64_t duration_ms, double rtt_ms, double loss_percent,
                                  std::uint64_t bytes_sent, std::uint64_t bytes_received) const {
  return link_stats_json(LinkSummary{predict_, predictor_.stats(), stalls_, response_, duration_ms, rtt_ms, loss_percent,
                                     jitter_.jitter_ms(), delay_ms_, bytes_sent, bytes_received, frames_,
                                     longest_gap_ms_, jitter_max_ms_});
}

void place_own_ball(protocol::Snapshot& s, std::uint32_t me, const protocol::BallState& own) {
  for (auto& b : s.balls)
    if (b.kind == protocol::BallKind::player && b.owner == me) b.x = own.x, b.y = own.y, b.vx = own.vx, b.vy = own.vy;
}

void place_near_balls(protocol::Snapshot& s, const std::vector<protocol::BallState>& near,
                      const protocol::BallState& own, double full_u, double none_u) {
  for (const auto& p : near) {
    const double gap = std::hypot(p.x - own.x, p.y - own.y) - p.radius - own.radius;
    const double w = none_u > full_u ? std::clamp((none_u - gap) / (none_u - full_u), 0.0, 1.0) : (gap <= full_u ? 1.0 : 0.0);
    if (w <= 0) continue;
    for (auto& b : s.balls)
      if (b.id == p.id) {
        b.x += w * (p.x - b.x);
        b.y += w * (p.y - b.y);
        b.vx += w * (p.vx - b.vx);
        b.vy += w * (p.vy - b.vy);
      }
  }
}

}  // namespace fts::client
