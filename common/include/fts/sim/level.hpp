// Levels: the enemy count n(L), each enemy's mass/radius/speed, goal boxes and spawns.
#pragma once

#include <cstdint>
#include <vector>

#include "fts/sim/ball.hpp"
#include "fts/sim/broadphase.hpp"
#include "fts/sim/config.hpp"
#include "fts/sim/rng.hpp"

namespace fts::sim {

bool is_boss_level(std::int64_t level, const MatchConfig& cfg);
bool is_swarm_level(std::int64_t level, const MatchConfig& cfg);
// n(L) for one player.
std::int64_t enemy_count(std::int64_t level, const MatchConfig& cfg);
// n(L) x players, capped at cfg.enemies_cap (at least 1 player counted).
std::int64_t enemy_count_for_players(std::int64_t level, std::int64_t players, const MatchConfig& cfg);

enum class EnemyRole : std::uint8_t { still, wanderer, chaser };

struct EnemySpec {
  double mass = 0.0;
  double radius_u = 0.0;
  double accel_u_per_s2 = 0.0;
  double vmax_u_per_s = 0.0;
  EnemyRole role = EnemyRole::wanderer;
};

// The enemy of index `index` (0-based) on level L. Draws the normal enemy's mass jitter
// j = U(1..4) x U(-1..1) from rng (two draws, in that order); other kinds draw nothing.
EnemySpec enemy_spec(std::int64_t level, std::int64_t index, Rng& rng, const MatchConfig& cfg);

// Half-size of the box (centred on the platform) in which wander goals are drawn.
Vec2 goal_half_size(std::int64_t level, const MatchConfig& cfg);
// A goal point drawn uniformly in that box (x first, then y).
Vec2 draw_goal(std::int64_t level, Rng& rng, const MatchConfig& cfg);

// True when a ball of `radius` at `pos` keeps `gap` from every ball of `balls`.
bool is_free(const std::vector<Ball>& balls, Vec2 pos, double radius, double gap);
// A uniformly drawn point in `region` where a ball of `radius` is free (cfg.spawn_gap_u),
// redrawn until it fits. After cfg.spawn_attempts failed draws the whole platform is
// tried as many times; after that the last draw is used (the physics separates it).
Vec2 find_spawn(const std::vector<Ball>& balls, double radius, const Box& region, Rng& rng,
                const MatchConfig& cfg);
// The enemies' spawn box [50, 450] x [50, 250].
Box enemy_spawn_box(const MatchConfig& cfg);

}  // namespace fts::sim
