// Client-side prediction of the own ball (issue 28), with reconciliation and smoothing.
//
// The client runs ahead of the newest snapshot by about a round trip: the input it
// decides now reaches the server at a later tick, and every input frame names that tick
// (PROTOCOL.md 4.5), so the server applies it exactly there. To draw its own ball at that
// tick the client steps common/'s physics (sim::apply_thrust, then sim::step: the same
// functions, settings and constants as the match) from the newest authoritative state of
// the ball, re-applying its own inputs since (Quake III's and Source's prediction).
//
// Reconciliation: each snapshot is a new base; the ball is predicted again from it to the
// tick on screen, and the difference to what was drawn is a correction. A small one is
// blended out over a few frames (the drawn ball keeps an offset that decays), a large one
// (over snap_radii ball radii: a collision the prediction did not know) is snapped, and
// both are counted. What is predicted: the own ball alone, on an empty platform; other
// balls and collisions with them are not (BENCHMARKS.md "Issue 28" has the measurement
// behind that choice). Pure: ticks and times are passed in.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "fts/protocol/snapshot.hpp"
#include "fts/sim/config.hpp"
#include "fts/sim/physics.hpp"

namespace fts::client {

struct PredictionTuning {
  double snap_radii = 2.0;    // a correction larger than this many radii is snapped
  double blend_ms = 100.0;    // a smaller one decays with this time constant
  double tiny_u = 0.02;       // below this (quantization) a difference is no correction
};

// What reconciliation did (for the HUD, --stats-file and the benchmarks).
struct PredictionStats {
  std::uint64_t corrections = 0;        // blended
  std::uint64_t snaps = 0;              // snapped
  std::uint64_t contact_corrections = 0;  // of both, while another ball touched ours
  std::vector<double> free_sizes_radii;   // sizes of corrections while nothing touched ours
  std::vector<double> all_sizes_radii;    // every correction's size (ball radii)
};

// How far ahead of the server clock a predicting client draws its own ball and stamps
// its frames (PROTOCOL.md 4.5.1): about a round trip, so that a frame sent now arrives
// before its tick. The lead grows toward its target by at most half the ticks that pass
// (frames late while it is short cost corrections) and shrinks by at most 10 % of them
// (the own ball's time slows by 10 %, unseen); the frames' ticks never go back.
class LeadClock {
 public:
  // The tick to draw the own ball at, from the server clock's estimate now.
  double predicted(double server_tick, double rtt_ms, double jitter_ms, double tick_rate_hz, std::uint64_t now_ms);
  // The tick for a frame sent now (>= 1, never before the last one).
  std::uint32_t stamp(double predicted_tick);
  double lead_ticks() const { return lead_ticks_; }

  static constexpr double kMarginMs = 10;

 private:
  double lead_ticks_ = 0;
  std::uint64_t last_ms_ = 0;
  std::int64_t stamp_ = 0;
};

class OwnBallPredictor {
 public:
  // `cfg`: the match's configuration as the welcome carries it (Welcome::match): the
  // step runs with exactly its physics (defaults if the step could not run on it).
  explicit OwnBallPredictor(const sim::MatchConfig& cfg = {}, PredictionTuning tuning = {});

  // The input in force from `tick` on (the frame sent stamped with that tick).
  void input(std::int64_t tick, int dx, int dy);
  // An authoritative snapshot; `me`: our player id. Our ball absent (fallen, not in the
  // match): nothing is predicted until it is back. `shown_tick`: the tick drawn now (the
  // correction is measured there).
  void on_snapshot(const protocol::Snapshot& s, std::uint32_t me, double shown_tick, std::uint64_t now_ms);
  // Our ball to draw at (fractional) tick `tick`, with the correction still being blended
  // out; nothing without a base.
  std::optional<protocol::BallState> at(double tick, std::uint64_t now_ms);

  const PredictionStats& stats() const { return stats_; }
  std::int64_t base_tick() const { return base_ ? base_tick_ : -1; }

 private:
  // The state predicted for `tick` (>= base), stepping on from the cache.
  const sim::Ball* state_at(std::int64_t tick);
  void step_once();
  std::pair<int, int> input_at(std::int64_t tick) const;
  double offset_factor(std::uint64_t now_ms) const;

  PredictionTuning k_;
  sim::PhysicsSettings physics_;
  sim::StepConstants step_k_;
  double tick_rate_hz_ = 100;
  sim::World world_;                  // the cache: our ball at cache_tick_ (or fallen)
  std::int64_t cache_tick_ = 0;
  bool fallen_ = false;
  std::optional<sim::Ball> base_;      // our ball in the newest snapshot
  std::int64_t base_tick_ = 0;
  double accel_ = 200, vmax_ = 170;    // our player's, from the snapshot
  std::map<std::int64_t, std::pair<int, int>> inputs_;  // tick -> (dx, dy) in force from it
  double offset_x_ = 0, offset_y_ = 0;  // drawn minus predicted, decaying
  std::uint64_t offset_ms_ = 0;         // when the offset was last set
  PredictionStats stats_;
};

}  // namespace fts::client
