// Shared pieces of the three models (internal to fts_common).
#pragma once

#include <utility>
#include <vector>

#include "fts/sim/broadphase.hpp"
#include "fts/sim/physics.hpp"

namespace fts::sim::detail {

using IndexPair = std::pair<std::uint32_t, std::uint32_t>;

bool use_grid(const PhysicsSettings& s, std::size_t bodies);

// After a move: fold positions back into a walled box (any number of reflections), or
// remove balls whose centre left an open rectangle (ids appended to report.fallen).
void apply_boundary(World& world, StepReport& report);

// The move of a (sub)step: positions advance by vel * h, then the boundary as above, in
// one pass in a walled box, which also adds every ball to `bounds` (when given) and
// lists in `unsettled` the balls rounding left outside after their fold.
void advance(World& world, double h, StepReport& report, DiscBounds* bounds, std::vector<std::uint32_t>& unsettled);
// After a push-apart: the boundary again, in a walled box only for the balls listed in
// `unsettled` (the ones pushed plus those advance() listed; the others have not moved
// since they were folded), in index order, as a pass over every ball would.
void settle(World& world, std::vector<std::uint32_t>& unsettled, StepReport& report);

// Every overlapping pair (d <= r1 + r2) as index pairs (i < j) in ascending order, so
// that "pairs" and "grid" resolve contacts in the same order. `bounds`: as for
// DiscGrid::touching_pairs (grid mode only).
void find_overlaps(const std::vector<Ball>& balls, bool grid_mode, DiscGrid& grid, std::vector<IndexPair>& out,
                   const DiscBounds* bounds = nullptr);

void step_seed(World& world, const PhysicsSettings& s, double dt, StepReport& report);
void step_discrete(World& world, const PhysicsSettings& s, double dt, StepReport& report);
void step_continuous(World& world, const PhysicsSettings& s, double dt, StepReport& report);

// Rebuilds the continuous model's skin for these balls and tick (skin_pairs, near,
// origins; the wakes only sized: after the build the caller marks every ball's course
// with the solve before skin_tick, which makes every pair due): step_skin.cpp.
void build_continuous_skin(const std::vector<Ball>& balls, double dt, StepBuffers& skin);

}  // namespace fts::sim::detail
