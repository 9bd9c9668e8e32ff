// The memory one physics step works in, owned by the world that is stepped (as Box2D
// v3's world owns its per-step stack): no thread_local scratch, no buffer borrowed from
// elsewhere. Capacity is all that survives a step; every step rebuilds the contents.
// So copying a world copies no buffers: the copy starts with empty ones.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "fts/sim/broadphase.hpp"
#include "fts/sim/broadphase_discs.hpp"

namespace fts::sim {

namespace detail {
// A ball-ball or ball-edge event of the continuous model (see step_continuous.cpp).
struct TimedEvent {
  double t;                         // s from the start of the tick
  std::uint32_t a, b;               // ball indices; b may be an edge code
  std::uint32_t stamp_a, stamp_b;   // the balls' stamps when it was predicted
};
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
  // Continuous model: per-ball clock, stamp, liveness, escape flag; the event heap.
  std::vector<double> t;
  std::vector<std::uint32_t> stamp;
  std::vector<std::uint8_t> alive;
  std::vector<std::uint8_t> escaped_flag;
  std::vector<std::uint32_t> escaped;
  std::vector<Box> escaped_box;  // an escaped ball's path box until its next event
  std::vector<detail::TimedEvent> heap;
};

}  // namespace fts::sim
