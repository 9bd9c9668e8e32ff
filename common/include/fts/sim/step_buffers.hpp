// The memory one physics step works in, owned by the world that is stepped (as Box2D
// v3's world owns its per-step stack): no thread_local scratch, no buffer borrowed from
// elsewhere. Capacity survives a step, and the continuous model's caches: its skin grid
// and its working copies of the balls (below), checked against the balls at every step,
// refreshed where a ball changed and rebuilt when they no longer cover them, so results
// never depend on them. Copying a world copies no buffers: the copy starts with empty
// ones (and builds its own caches), and steps to the same bits.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "fts/sim/big_vector.hpp"
#include "fts/sim/broadphase.hpp"
#include "fts/sim/broadphase_discs.hpp"
#include "fts/sim/vec2.hpp"

namespace fts::sim {

namespace detail {
// A ball-ball or ball-edge event of the continuous model (see step_continuous.cpp).
struct TimedEvent {
  double t;                         // s from the start of the tick
  std::uint32_t a, b;               // ball indices; b may be an edge code
  std::uint32_t stamp_a, stamp_b;   // the balls' stamps when it was predicted
};

// The continuous model's working copy of a ball: what an event reads or writes about a
// ball in one cache line (at 10^5 balls, the separate arrays it replaced cost an event
// one miss each). Between solves it holds what the last solve left (pos at the end of
// the tick, t = 0), against which the next one finds the balls changed from outside.
struct alignas(64) SolverBall {
  Vec2 pos, vel;
  double radius, mass;
  double t;                 // the ball's clock within the tick: pos is where it is at t
  std::uint32_t stamp;      // bumped by each of its events (an event names both stamps)
  std::uint32_t near;       // grid mode: where its neighbours start in StepBuffers::near
};
// Ends each ball's neighbours in StepBuffers::near.
inline constexpr std::uint32_t kEndOfNear = 0xffffffffu;
static_assert(sizeof(SolverBall) == 64);
}  // namespace detail

struct StepBuffers {
  StepBuffers() = default;
  StepBuffers(const StepBuffers&) {}
  StepBuffers& operator=(const StepBuffers&) { return *this; }
  StepBuffers(StepBuffers&&) noexcept = default;
  StepBuffers& operator=(StepBuffers&&) noexcept = default;
  ~StepBuffers() = default;

  DiscGrid discs;                                           // overlap search (seed, discrete)
  Grid grid;                                                // swept boxes (continuous)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // overlapping index pairs
  std::vector<std::uint32_t> unsettled;  // seed, discrete: balls to fold into the walls again
  // Continuous model: the balls' working copies, liveness, escape flag; the event heap.
  BigVector<detail::SolverBall> bodies;
  BigVector<std::uint8_t> alive;
  BigVector<std::uint8_t> escaped_flag;
  std::vector<std::uint32_t> escaped;
  std::vector<Box> escaped_box;  // per escaped ball, in escaped's order: its path until its next event
  BigVector<std::uint32_t> escaped_slot;  // per ball, while escaped: its place in escaped
  BigVector<std::uint32_t> edge_due;  // balls that may reach an edge this tick (grid mode; a prefix)
  std::vector<detail::TimedEvent> heap;
  // Continuous model, grid mode: the skin cache. Each ball's skin box is its position at
  // the last build +- (radius + half_skin); `grid` indexes those boxes and `skin_pairs`
  // lists the pairs whose skin discs overlap (i < j; `near` the same per ball, each list
  // ended by kEndOfNear, so that the ball's copy, holding where its list starts, is all
  // a refresh reads first). A ball whose whole path stays within half_skin of its
  // `skin_origin` can only meet its listed neighbours and the balls that left their own
  // skin (step_continuous.cpp).
  BigVector<Vec2> skin_origin;
  // The ball ids it was built for (the radii are the balls' copies'): any change (a ball
  // added, removed, resized) rebuilds.
  BigVector<std::uint32_t> skin_id;
  BigVector<std::pair<std::uint32_t, std::uint32_t>> skin_pairs;
  BigVector<std::uint32_t> near_start;  // ball i's neighbours: near[near_start[i]] .. kEndOfNear
  BigVector<std::uint32_t> near;
  BigVector<std::uint32_t> near_fill;   // build scratch
  // Predictions kept across ticks (grid mode): skin pair p was last predicted at the
  // start of solve `seen` and cannot meet before the start of solve `wake` while both
  // balls keep their lines; course[i] is the last solve in which ball i's line changed
  // (an event, or a change between solves: its position, velocity or mass differs from
  // what the previous solve left).
  struct PairWake {
    std::uint32_t seen = 0, wake = 0;
  };
  BigVector<PairWake> pair_wake;  // parallel to skin_pairs
  BigVector<std::uint32_t> course;
  std::uint32_t skin_tick = 0;  // solves in grid mode
  double skin_dt = 0.0;         // the tick the skin and the wakes were made for
  double half_skin = 0.0;
  bool skin_valid = false;
  std::uint64_t skin_builds = 0;  // how often it was rebuilt (benchmarks and tests)
};

}  // namespace fts::sim
