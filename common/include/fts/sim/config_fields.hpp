// Every field of MatchConfig, once, in declaration order, with who needs it (issue 36).
//   CLIENT(name, lo, hi, presence): a client needs it too (its prediction steps the own
//     ball with it, its shop screen states it): the welcome carries it (PROTOCOL.md 4.3), a
//     reader accepts lo..hi (a name for the model); `required`: always written (readers of
//     version 3 before issue 36 need it), `optional`: written when it is not the default
//     (what an older server's welcome lacks reads as the default; and a welcome must fit
//     in the reply to a hello, 5.1). The welcome's rows are made from this list.
//   HOST(name): the match's alone; no client reads it.
// A new field goes here (its config key follows), and must say which it is. The config
// file's table (protocol/room/src/match_config_json.cpp), the welcome's
// (protocol/src/control_tables.hpp) and client_part() are expanded from this one list.
#pragma once

#include "fts/sim/config.hpp"

// clang-format off
#define FTS_MATCH_CONFIG_FIELDS(CLIENT, HOST)                                                       \
  CLIENT(tick_rate_hz, 1, 10000, required) CLIENT(model, 0, 2, optional)                           \
  CLIENT(substeps, 1, 1024, optional) HOST(max_players) CLIENT(frame_s, 1e-6, 1e6, required)        \
  CLIENT(arena_width_u, 0, 1e6, required) CLIENT(arena_height_u, 0, 1e6, required)                  \
  HOST(spawn_margin_u) HOST(spawn_gap_u) HOST(spawn_attempts)                                       \
  CLIENT(friction_per_frame, 0, 1, optional) CLIENT(friction_cutoff_u_per_s, 0, 1e6, optional)      \
  HOST(radius_base_u) HOST(radius_mass_divisor) HOST(player_mass) HOST(player_vmax_u_per_s)         \
  HOST(player_accel_u_per_s2) HOST(player_lives) HOST(player_coins) HOST(player_multiplier)         \
  HOST(respawn_delay_s) HOST(player_spawn_x_fraction) HOST(spawn_protection_s) HOST(late_join_share) \
  HOST(enemies_max_normal) HOST(enemies_min_late) HOST(boss_period) HOST(boss_count)                \
  HOST(boss_double_period) HOST(boss_double_count) HOST(swarm_phase) HOST(swarm_count)              \
  HOST(enemies_cap) HOST(chaser_index) HOST(level1_enemy_mass) HOST(normal_mass_base)               \
  HOST(normal_mass_per_level) HOST(normal_mass_per_q) HOST(normal_mass_jitter)                      \
  HOST(normal_accel_base_u_per_frame2) HOST(normal_accel_per_level) HOST(normal_accel_per_q)        \
  HOST(normal_vmax_base_u_per_frame) HOST(normal_vmax_per_level) HOST(normal_vmax_per_q)            \
  HOST(swarm_mass_per_q1) HOST(swarm_radius_base_u) HOST(swarm_radius_per_q)                        \
  HOST(swarm_vmax_base_u_per_frame) HOST(swarm_vmax_per_level) HOST(swarm_vmax_per_q)               \
  HOST(swarm_accel_base_u_per_frame2) HOST(swarm_accel_per_level) HOST(swarm_accel_per_q)           \
  HOST(boss_mass_per_q) HOST(boss_mass_per_pair) HOST(boss_radius_base_u)                           \
  HOST(boss_vmax_base_u_per_frame) HOST(boss_vmax_per_q) HOST(boss_accel_base_u_per_frame2)         \
  HOST(boss_accel_per_q) HOST(goal_half_w_u) HOST(goal_half_h_u) HOST(goal_shrink_per_level_u)      \
  HOST(goal_shrink_level_cap) HOST(boss_goal_half_w_u) HOST(boss_goal_half_h_u) HOST(goal_reach_u)  \
  HOST(reward_level_bonus) HOST(credit_chain_s) CLIENT(bank_interest_factor, 0, 1e6, required)      \
  HOST(level_multiplier_growth) HOST(level_life_price_growth) HOST(price_mass)                      \
  HOST(price_mass_level_coeff) HOST(price_mass_offset) HOST(price_speed) HOST(price_speed_growth)   \
  HOST(speed_upgrade_factor) HOST(price_accel) HOST(price_accel_growth) HOST(accel_upgrade_factor)  \
  HOST(price_rockets) HOST(price_life) HOST(price_life_growth) HOST(price_multiplier)               \
  HOST(price_multiplier_growth) CLIENT(multiplier_upgrade_factor, 0, 1e6, required) HOST(price_bank) \
  HOST(shop_timeout_s) HOST(lobby_timeout_s) HOST(rocket_cooldown_s) HOST(rocket_mass)              \
  HOST(rocket_radius_u) HOST(rocket_speed_factor) HOST(rocket_lifetime_s) HOST(coin_cap)            \
  HOST(multiplier_cap) HOST(player_vmax_cap_u_per_s) HOST(player_accel_cap_u_per_s2)                \
  HOST(player_mass_cap) HOST(lives_cap)
// clang-format on

namespace fts::sim {

// The fields a client needs (CLIENT above) copied from cfg, every other at its default:
// what the welcome carries, and all a client knows of the match's configuration.
MatchConfig client_part(const MatchConfig& cfg);

}  // namespace fts::sim
