// What a client keeps beside its snapshots to play over a real network (issue 28,
// PROTOCOL.md 4.5.1): the server clock, the jitter buffer (the remote balls' delay), the
// lead and the own-ball predictor, and the meters of what they did (--stats-file).
// fts-client draws with it; fts-bot --predict runs the same, so load tests pay the
// client's CPU. Pure: times are passed in.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "fts/protocol/messages.hpp"
#include "fts/protocol/snapshot.hpp"
#include "net/interpolate.hpp"
#include "net/jitter_buffer.hpp"
#include "net/link_meters.hpp"
#include "net/link_stats.hpp"
#include "predict/prediction.hpp"

namespace fts::client {

class NetTiming {
 public:
  // `predict`: run the own-ball prediction (fts-client --no-predict, fts-bot without
  // --predict: only the clock and the delay); `tuning`: the prediction's (fts-bot
  // --predict-own-only: the own ball alone, as before issue 37).
  explicit NetTiming(bool predict = true, PredictionTuning tuning = {}) : predict_(predict), tuning_(tuning) {}

  // The welcome's rates and platform: the clock's rate, the snapshot interval, the
  // prediction's world. A welcome starts a session (the first or a reconnect): the clock,
  // the jitter buffer, the lead and the loss meter start afresh, since what they learnt
  // of the old session's link (a gap of a minute read as loss and lateness) is not this
  // one's (issue 37).
  void on_welcome(const protocol::Welcome& w);
  // A complete snapshot arrived; `me`: our player id.
  void on_snapshot(const protocol::Snapshot& s, std::uint32_t me, std::uint64_t now_ms);

  bool predicting() const { return predict_ && jitter_.clock().valid(); }
  double tick_rate_hz() const { return tick_rate_hz_; }
  // The server's tick as seen now (0 before the first snapshot).
  double server_tick(std::uint64_t now_ms) const { return jitter_.clock().tick_at(now_ms); }
  // Predicting: the tick the own ball is drawn at now (remembered for the next snapshot's
  // correction), and the tick a frame sent now names.
  double own_tick(std::uint64_t now_ms, double rtt_ms);
  double shown_tick() const { return shown_tick_; }
  std::uint32_t stamp(double own_tick) { return lead_.stamp(own_tick); }
  // A frame that went out (what the server will apply from its tick).
  void sent(const protocol::InputFrame& f);
  // The own ball at the tick own_tick() gave last, or nothing (no base, fallen).
  std::optional<protocol::BallState> own_ball(std::uint64_t now_ms) { return predictor_.at(shown_tick_, now_ms); }
  // The balls stepped with ours, at the same tick (issue 37: a hit is drawn where it happens).
  std::vector<protocol::BallState> near_balls() { return predictor_.others_at(shown_tick_); }
  // The remote balls' delay now (`fixed`: --interp-delay-ms), and the tick they are drawn at.
  double remote_tick(std::uint64_t now_ms, std::optional<int> fixed_ms);
  double remote_delay_ms() const { return delay_ms_; }

  // Meters: a frame drawn (stalled: nothing newer than the remote tick), the thrust
  // decided this frame, the own ball's drawn velocity.
  void frame_drawn(bool stalled, std::uint64_t now_ms);
  void thrust(int dx, int dy, std::uint64_t now_ms) { response_.thrust(dx, dy, drawn_vx_, drawn_vy_, now_ms); }
  void drawn(double vx, double vy, std::uint64_t now_ms);

  const PredictionStats& prediction() const { return predictor_.stats(); }
  const OwnBallPredictor& predictor() const { return predictor_; }
  double lead_ticks() const { return lead_.lead_ticks(); }
  double jitter_ms() const { return jitter_.jitter_ms(); }
  // Snapshots lost in this session, recently (0..100; < 0 before there is anything to judge).
  double loss_percent() const { return loss_.percent(); }
  // The session's figures as one JSON object (--stats-file).
  std::string stats_json(std::uint64_t duration_ms, double rtt_ms, double loss_percent, std::uint64_t bytes_sent,
                         std::uint64_t bytes_received) const;

 private:
  bool predict_;
  PredictionTuning tuning_;
  double tick_rate_hz_ = 100;
  JitterBuffer jitter_;  // and the server clock it measures lateness against
  LeadClock lead_;
  OwnBallPredictor predictor_;
  LossMeter loss_;
  double ticks_per_snapshot_ = 5;
  double shown_tick_ = 0;
  double delay_ms_ = 0;
  StallMeter stalls_;
  ResponseMeter response_;
  double drawn_vx_ = 0, drawn_vy_ = 0;
  std::uint64_t frames_ = 0;
  std::uint64_t last_arrival_ms_ = 0, longest_gap_ms_ = 0;  // between snapshots' arrivals (stats)
  double jitter_max_ms_ = 0;                                // the highest lateness estimate (stats)
};

// `s` with our ball (owner `me`) moved to `own` (the prediction drawn in place of the
// snapshot's).
void place_own_ball(protocol::Snapshot& s, std::uint32_t me, const protocol::BallState& own);

// `s` with the balls predicted near ours (`near`, NetTiming::near_balls()) drawn at their
// predicted places: wholly where their edge is within `full_u` of the own ball's, not at
// all from `none_u` on, in between a mix, so that a ball coming near slides from the
// remote balls' time into the own ball's rather than jumping.
void place_near_balls(protocol::Snapshot& s, const std::vector<protocol::BallState>& near,
                      const protocol::BallState& own, double full_u = 60, double none_u = 120);

}  // namespace fts::client
