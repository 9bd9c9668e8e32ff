#include "fts/sim/level.hpp"

#include <algorithm>
#include <cmath>

namespace fts::sim {
namespace {

std::int64_t mod(std::int64_t a, std::int64_t m) { return ((a % m) + m) % m; }

double per_frame_to_per_s(double v, const MatchConfig& cfg) { return v / cfg.frame_s; }
double per_frame2_to_per_s2(double a, const MatchConfig& cfg) { return a / (cfg.frame_s * cfg.frame_s); }

}  // namespace

bool is_boss_level(std::int64_t level, const MatchConfig& cfg) { return mod(level, cfg.boss_period) == 0; }

bool is_swarm_level(std::int64_t level, const MatchConfig& cfg) {
  return mod(level, cfg.boss_period) == cfg.swarm_phase;
}

std::int64_t enemy_count(std::int64_t level, const MatchConfig& cfg) {
  const std::int64_t L = std::max<std::int64_t>(level, 1);
  std::int64_t n = L;
  if (n > cfg.enemies_max_normal) n = cfg.enemies_max_normal - L / cfg.boss_period;
  if (n < cfg.enemies_min_late && L > cfg.enemies_min_late) n = cfg.enemies_min_late;
  if (is_boss_level(L, cfg)) n = mod(L, cfg.boss_double_period) == 0 ? cfg.boss_double_count : cfg.boss_count;
  if (is_swarm_level(L, cfg)) n = cfg.swarm_count;
  return std::max<std::int64_t>(n, 1);
}

std::int64_t enemy_count_for_players(std::int64_t level, std::int64_t players, const MatchConfig& cfg) {
  const std::int64_t k = std::clamp<std::int64_t>(players, 1, 4096);
  return std::min(enemy_count(level, cfg) * k, cfg.enemies_cap);
}

EnemySpec enemy_spec(std::int64_t level, std::int64_t index, Rng& rng, const MatchConfig& cfg) {
  const std::int64_t L = std::max<std::int64_t>(level, 1);
  const double Ld = static_cast<double>(L);
  const double q = static_cast<double>(L / cfg.boss_period);
  EnemySpec e;
  if (L == 1) {
    e.mass = cfg.level1_enemy_mass;
    e.radius_u = radius_for_mass(cfg, e.mass);
    e.role = EnemyRole::still;
    return e;
  }
  const std::int64_t n = enemy_count(L, cfg);
  e.role = (index % n) == cfg.chaser_index ? EnemyRole::chaser : EnemyRole::wanderer;
  if (is_boss_level(L, cfg)) {
    const double pairs = static_cast<double>((L - cfg.boss_period) / cfg.boss_double_period);
    e.mass = std::max(1.0, cfg.boss_mass_per_q * q - cfg.boss_mass_per_pair * pairs);
    e.radius_u = cfg.boss_radius_base_u + std::floor(e.mass / cfg.radius_mass_divisor);
    e.vmax_u_per_s = per_frame_to_per_s(cfg.boss_vmax_base_u_per_frame + cfg.boss_vmax_per_q * q, cfg);
    e.accel_u_per_s2 = per_frame2_to_per_s2(cfg.boss_accel_base_u_per_frame2 + cfg.boss_accel_per_q * q, cfg);
  } else if (is_swarm_level(L, cfg)) {
    e.mass = cfg.swarm_mass_per_q1 * (q + 1.0);
    e.radius_u = cfg.swarm_radius_base_u + std::floor(cfg.swarm_radius_per_q * q + 1e-9);
    e.vmax_u_per_s = per_frame_to_per_s(
        cfg.swarm_vmax_base_u_per_frame + cfg.swarm_vmax_per_level * Ld + cfg.swarm_vmax_per_q * q, cfg);
    e.accel_u_per_s2 = per_frame2_to_per_s2(
        cfg.swarm_accel_base_u_per_frame2 + cfg.swarm_accel_per_level * Ld + cfg.swarm_accel_per_q * q, cfg);
  } else {
    const std::int64_t j1 = rng.uniform_int(1, cfg.normal_mass_jitter < 1 ? 1 : cfg.normal_mass_jitter);
    const std::int64_t j2 = rng.uniform_int(-1, 1);
    const double j = cfg.normal_mass_jitter < 1 ? 0.0 : static_cast<double>(j1 * j2);
    // 1e-9 keeps floor(2.1 L) exact where 2.1 L is an integer but rounds just below it.
    e.mass = std::max(1.0, cfg.normal_mass_base + std::floor(cfg.normal_mass_per_level * Ld + 1e-9) +
                               cfg.normal_mass_per_q * q + j);
    e.radius_u = radius_for_mass(cfg, e.mass);
    e.vmax_u_per_s = per_frame_to_per_s(
        cfg.normal_vmax_base_u_per_frame + cfg.normal_vmax_per_level * Ld + cfg.normal_vmax_per_q * q, cfg);
    e.accel_u_per_s2 = per_frame2_to_per_s2(
        cfg.normal_accel_base_u_per_frame2 + cfg.normal_accel_per_level * Ld + cfg.normal_accel_per_q * q, cfg);
  }
  e.vmax_u_per_s = std::max(0.0, e.vmax_u_per_s);
  e.accel_u_per_s2 = std::max(0.0, e.accel_u_per_s2);
  return e;
}

Vec2 goal_half_size(std::int64_t level, const MatchConfig& cfg) {
  if (is_boss_level(level, cfg)) return {cfg.boss_goal_half_w_u, cfg.boss_goal_half_h_u};
  const double l = static_cast<double>(std::min(std::max<std::int64_t>(level, 1), cfg.goal_shrink_level_cap));
  const double s = cfg.goal_shrink_per_level_u * l;
  return {std::max(0.0, cfg.goal_half_w_u - s), std::max(0.0, cfg.goal_half_h_u - s)};
}

Vec2 draw_goal(std::int64_t level, Rng& rng, const MatchConfig& cfg) {
  const Vec2 h = goal_half_size(level, cfg);
  const Vec2 c{cfg.arena_width_u * 0.5, cfg.arena_height_u * 0.5};
  const double x = rng.uniform(c.x - h.x, c.x + h.x);
  const double y = rng.uniform(c.y - h.y, c.y + h.y);
  return {x, y};
}

bool is_free(const std::vector<Ball>& balls, Vec2 pos, double radius, double gap) {
  for (const Ball& b : balls) {
    const double reach = b.radius + radius + gap;
    if (length_sq(b.pos - pos) < reach * reach) return false;
  }
  return true;
}

Box enemy_spawn_box(const MatchConfig& cfg) {
  const double m = cfg.spawn_margin_u;
  return {m, m, cfg.arena_width_u - m, cfg.arena_height_u - m};
}

Vec2 find_spawn(const std::vector<Ball>& balls, double radius, const Box& region, Rng& rng,
                const MatchConfig& cfg) {
  Vec2 p;
  for (std::int64_t i = 0; i < cfg.spawn_attempts; ++i) {
    p.x = rng.uniform(region.x0, region.x1);
    p.y = rng.uniform(region.y0, region.y1);
    if (is_free(balls, p, radius, cfg.spawn_gap_u)) return p;
  }
  const double rx = std::min(radius, cfg.arena_width_u * 0.5), ry = std::min(radius, cfg.arena_height_u * 0.5);
  for (std::int64_t i = 0; i < cfg.spawn_attempts; ++i) {
    p.x = rng.uniform(rx, cfg.arena_width_u - rx);
    p.y = rng.uniform(ry, cfg.arena_height_u - ry);
    if (is_free(balls, p, radius, cfg.spawn_gap_u)) return p;
  }
  return p;
}

}  // namespace fts::sim
