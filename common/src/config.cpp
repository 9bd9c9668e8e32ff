#include "fts/sim/config.hpp"

#include <cmath>

namespace fts::sim {

std::int64_t ticks_for(const MatchConfig& cfg, double seconds) {
  const double t = std::round(seconds * cfg.tick_rate_hz);
  if (!(t >= 1.0)) return 1;
  if (t > 1e15) return 1'000'000'000'000'000;
  return static_cast<std::int64_t>(t);
}

double radius_for_mass(const MatchConfig& cfg, double mass) {
  return cfg.radius_base_u + std::floor(mass / cfg.radius_mass_divisor);
}

PhysicsSettings physics_settings(const MatchConfig& cfg) {
  PhysicsSettings s;
  s.model = cfg.model;
  s.substeps = cfg.substeps;
  s.friction = true;
  s.friction_per_frame = cfg.friction_per_frame;
  s.frame_s = cfg.frame_s;
  s.friction_cutoff_u_per_s = cfg.friction_cutoff_u_per_s;
  return s;
}

std::string validate(const MatchConfig& c) {
  auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto nonneg = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!(c.tick_rate_hz >= 1.0 && c.tick_rate_hz <= 10000.0)) return "tick_rate_hz must be in 1..10000";
  if (c.substeps < 1 || c.substeps > 1024) return "substeps must be in 1..1024";
  if (c.max_players < 1 || c.max_players > 64) return "max_players must be in 1..64";
  if (!pos(c.frame_s)) return "frame_s must be > 0";
  if (!pos(c.arena_width_u) || !pos(c.arena_height_u)) return "arena size must be > 0";
  if (!nonneg(c.spawn_margin_u) || 2.0 * c.spawn_margin_u >= c.arena_width_u ||
      2.0 * c.spawn_margin_u >= c.arena_height_u)
    return "spawn_margin_u must leave an inner box";
  if (!nonneg(c.spawn_gap_u)) return "spawn_gap_u must be >= 0";
  if (c.spawn_attempts < 1 || c.spawn_attempts > 1'000'000) return "spawn_attempts must be in 1..1000000";
  if (!(c.friction_per_frame > 0.0 && c.friction_per_frame <= 1.0)) return "friction_per_frame must be in (0, 1]";
  if (!nonneg(c.friction_cutoff_u_per_s)) return "friction_cutoff_u_per_s must be >= 0";
  if (!pos(c.radius_base_u) || !pos(c.radius_mass_divisor)) return "radius rule must be > 0";
  if (c.player_mass < 1 || c.player_mass > c.player_mass_cap) return "player_mass must be in 1..player_mass_cap";
  if (!pos(c.player_vmax_u_per_s) || !pos(c.player_accel_u_per_s2)) return "player speeds must be > 0";
  if (c.player_lives < 1 || c.player_lives > c.lives_cap) return "player_lives must be in 1..lives_cap";
  if (c.player_coins < 0 || c.player_coins > c.coin_cap) return "player_coins must be in 0..coin_cap";
  if (!pos(c.player_multiplier) || c.player_multiplier > c.multiplier_cap) return "player_multiplier must be in (0, multiplier_cap]";
  if (!nonneg(c.respawn_delay_s) || !nonneg(c.shop_timeout_s) || !nonneg(c.lobby_timeout_s) || !nonneg(c.credit_chain_s) ||
      !nonneg(c.spawn_protection_s))
    return "durations must be >= 0";
  if (!(c.late_join_share >= 0.0 && c.late_join_share <= 1.0)) return "late_join_share must be in 0..1";
  if (!(c.player_spawn_x_fraction > 0.0 && c.player_spawn_x_fraction < 1.0)) return "player_spawn_x_fraction must be in (0, 1)";
  if (c.enemies_max_normal < 1 || c.swarm_count < 1 || c.boss_count < 1 || c.boss_double_count < 1)
    return "enemy counts must be >= 1";
  if (c.enemies_min_late < 1) return "enemies_min_late must be >= 1";
  if (c.boss_period < 1 || c.boss_double_period < 1) return "boss periods must be >= 1";
  if (c.swarm_phase < 0 || c.swarm_phase >= c.boss_period) return "swarm_phase must be in 0..boss_period-1";
  if (c.enemies_cap < 1 || c.enemies_cap > 4096) return "enemies_cap must be in 1..4096";
  if (!pos(c.level1_enemy_mass)) return "level1_enemy_mass must be > 0";
  if (c.normal_mass_jitter < 0 || c.normal_mass_jitter > 1000) return "normal_mass_jitter must be in 0..1000";
  if (!nonneg(c.goal_half_w_u) || !nonneg(c.goal_half_h_u) || !nonneg(c.boss_goal_half_w_u) ||
      !nonneg(c.boss_goal_half_h_u) || !nonneg(c.goal_reach_u) || !std::isfinite(c.goal_shrink_per_level_u))
    return "goal box sizes must be >= 0";
  if (c.reward_level_bonus < 0) return "reward_level_bonus must be >= 0";
  for (double f : {c.bank_interest_factor, c.level_multiplier_growth, c.level_life_price_growth,
                   c.price_speed_growth, c.price_accel_growth, c.price_life_growth,
                   c.price_multiplier_growth, c.speed_upgrade_factor, c.accel_upgrade_factor,
                   c.multiplier_upgrade_factor})
    if (!(std::isfinite(f) && f >= 1.0 && f <= 1000.0)) return "growth factors must be in 1..1000";
  for (std::int64_t p : {c.price_mass, c.price_speed, c.price_accel, c.price_rockets, c.price_life,
                         c.price_multiplier, c.price_bank})
    if (p < 1 || p > c.coin_cap) return "prices must be in 1..coin_cap";
  if (!std::isfinite(c.price_mass_level_coeff) || !std::isfinite(c.price_mass_offset))
    return "mass price rule must be finite";
  if (!pos(c.rocket_cooldown_s) || !pos(c.rocket_mass) || !pos(c.rocket_radius_u) ||
      !pos(c.rocket_speed_factor) || !pos(c.rocket_lifetime_s))
    return "rocket figures must be > 0";
  if (c.coin_cap < 1 || c.coin_cap > 1'000'000'000'000'000) return "coin_cap must be in 1..10^15";
  if (!(c.multiplier_cap >= 1.0 && c.multiplier_cap <= 1e9)) return "multiplier_cap must be in 1..1e9";
  if (!pos(c.player_vmax_cap_u_per_s) || !pos(c.player_accel_cap_u_per_s2)) return "speed caps must be > 0";
  if (c.player_mass_cap < 1 || c.player_mass_cap > 1'000'000'000) return "player_mass_cap must be in 1..1e9";
  if (c.lives_cap < 1 || c.lives_cap > 1'000'000'000) return "lives_cap must be in 1..1e9";
  return {};
}

}  // namespace fts::sim
