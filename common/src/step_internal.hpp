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

// Every overlapping pair (d <= r1 + r2) as index pairs (i < j) in ascending order, so
// that "pairs" and "grid" resolve contacts in the same order.
void find_overlaps(const std::vector<Ball>& balls, bool grid_mode, DiscGrid& grid, std::vector<IndexPair>& out);

void step_seed(World& world, const PhysicsSettings& s, double dt, StepReport& report);
void step_discrete(World& world, const PhysicsSettings& s, double dt, StepReport& report);
void step_continuous(World& world, const PhysicsSettings& s, double dt, StepReport& report);

// Rebuilds the continuous model's skin for these balls and tick (skin_pairs, near,
// origins; every kept prediction dropped, skin_tick back to 1): step_skin.cpp.
void build_continuous_skin(const std::vector<Ball>& balls, double dt, StepBuffers& skin);

}  // namespace fts::sim::detail
