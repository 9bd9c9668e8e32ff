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
// both are counted.
//
// What is predicted (issue 37): the own ball and the balls near it, so that a hit on an
// enemy is drawn when it happens rather than corrected a round trip later. From the
// newest snapshot every ball whose edge is within PredictionTuning::near_gap_u of the own
// ball's edge (at most max_others of them, the nearest) is stepped with the own ball
// through common/'s step, collisions included, each thrusting as the server would have
// it thrust: an enemy with its level's acceleration and top speed (sim::enemy_spec), a
// remote player with its own; the direction each holds is the one that explains its
// velocity between the last two snapshots (the thrust the match applied, fitted per axis:
// the server's wanderers always thrust on both axes, toward a goal the client does not
// see), held until the next snapshot says otherwise. A ball under spawn protection is
// immovable, as in the match. Farther balls are not stepped (a collision with them is a
// correction, as before). Nothing here reaches the server: the frames carry inputs only.
// Pure: ticks and times are passed in.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "fts/protocol/snapshot.hpp"
#include "fts/sim/config.hpp"
#include "fts/sim/physics.hpp"

namespace fts::client {

// How the prediction steps another player's ball near ours: with the thrust that explains
// its last two snapshots held (its inputs are not known), coasting, or not at all.
enum class RemotePlayers : std::uint8_t { held, coast, off };
// The default (fts-client, and fts-bot's --predict-remote): coasting halved the contact
// corrections' p99 against held in every cell measured (issue 37,
// tests/bench/results/2026-12-05-contacts/exp-remote-modes and run3-coast: 0.19-0.31 radii
// at 150 ms with two remote players, held 0.42-0.56): a player turns too often for a
// thrust held a round trip later to be right.
inline constexpr RemotePlayers kDefaultRemotePlayers = RemotePlayers::coast;

struct PredictionTuning {
  double snap_radii = 2.0;    // a correction larger than this many radii is snapped
  double blend_ms = 100.0;    // a smaller one decays with this time constant
  double tiny_u = 0.02;       // below this (quantization) a difference is no correction
  bool others = true;         // step the balls near the own ball too (false: the own ball alone)
  double near_gap_u = 120.0;  // ...those whose edge is this close to the own ball's edge
  int max_others = 12;        // ...at most this many, the nearest
  RemotePlayers remote = kDefaultRemotePlayers;
};

// What reconciliation did (for the HUD, --stats-file and the benchmarks).
struct PredictionStats {
  std::uint64_t corrections = 0;        // blended
  std::uint64_t snaps = 0;              // snapped
  // Contact: at the snapshot that corrects, another ball is within the distance both could
  // have covered since the previous snapshot (edges 4 u apart, plus their speeds times the
  // time between the two): a contact in the corrected window, or a near miss.
  std::uint64_t contact_corrections = 0;  // of both, with a contact
  std::vector<double> free_sizes_radii;     // sizes of corrections while nothing touched ours
  std::vector<double> contact_sizes_radii;  // sizes of corrections with a contact
  std::vector<double> all_sizes_radii;      // every correction's size (ball radii)
  std::uint64_t balls_stepped = 0;          // ball-ticks stepped (the cost)
  std::uint64_t ticks_stepped = 0;          // ticks stepped
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

  // The other balls stepped with ours, at (fractional) tick `tick` as predicted (empty
  // without a base, with our ball fallen, or with `others` off): what a client draws near
  // its ball.
  std::vector<protocol::BallState> others_at(double tick);

  const PredictionStats& stats() const { return stats_; }
  std::int64_t base_tick() const { return base_ ? base_tick_ : -1; }
  // How many balls besides ours the newest base steps.
  std::size_t others_stepped() const { return base_world_.size() > 0 ? base_world_.size() - 1 : 0; }

 private:
  // How a ball other than ours thrusts in the prediction.
  struct Mover {
    std::uint32_t id = 0;
    int dx = 0, dy = 0;
    double accel = 0, vmax = 0;
    std::int64_t protected_until = -1;  // immovable while tick < this
    bool own = false;
  };
  // The state predicted for `tick` (>= base), stepping on from the cache.
  const sim::Ball* state_at(std::int64_t tick);
  const sim::Ball* own_in_cache() const;
  void step_once();
  std::pair<int, int> input_at(std::int64_t tick) const;
  double offset_factor(std::uint64_t now_ms) const;
  void choose_others(const protocol::Snapshot& s, const protocol::BallState& own, const protocol::PlayerState& me);
  // The thrust direction on one axis that takes v0 to v1 in n ticks (the match's thrust and
  // friction); `held` when none explains it (a collision in between).
  int fit_axis(double v0, double v1, std::int64_t n, double accel, double vmax, int held) const;

  PredictionTuning k_;
  sim::MatchConfig cfg_;
  sim::PhysicsSettings physics_;
  sim::StepConstants step_k_;
  double tick_rate_hz_ = 100;
  sim::World world_;                  // the cache: the predicted balls at cache_tick_
  std::vector<Mover> movers_;         // the cache's, by id (the own ball's protection ends when it acts)
  std::int64_t cache_tick_ = 0;
  bool fallen_ = false;
  std::optional<sim::Ball> base_;      // our ball in the newest snapshot
  std::vector<sim::Ball> base_world_;  // every ball stepped, from the newest snapshot (by id)
  std::vector<Mover> base_movers_;
  std::int64_t base_tick_ = 0;
  double accel_ = 200, vmax_ = 170;    // our player's, from the snapshot
  std::map<std::int64_t, std::pair<int, int>> inputs_;  // tick -> (dx, dy) in force from it
  // The previous snapshot's balls and each one's fitted thrust, to fit the next.
  std::vector<protocol::BallState> prev_balls_;
  std::int64_t prev_tick_ = -1;
  std::map<std::uint32_t, std::pair<int, int>> held_;
  double offset_x_ = 0, offset_y_ = 0;  // drawn minus predicted, decaying
  std::uint64_t offset_ms_ = 0;         // when the offset was last set
  PredictionStats stats_;
};

}  // namespace fts::client
