// Every field of MatchConfig, once, in declaration order, with who needs it (issue 36),
// as a field table (fts/sim/field_table.hpp, issue 38):
//   client_row(key, member, lo, hi, presence): a client needs it too (its prediction steps
//     the own ball with it, its shop screen states it): the welcome carries it (PROTOCOL.md
//     4.3), a reader accepts lo..hi (a name for the model); Presence::required: always
//     written (readers of version 3 before issue 36 need it), Presence::nonzero: written
//     when it is not the default (what an older server's welcome lacks reads as the
//     default; and a welcome must fit in the reply to a hello, 5.1).
//   host_row(key, member): the match's alone; no client reads it.
// A new field goes here (its config key follows), and must say which it is; a member with
// no row does not build (the static_assert in config_fields.cpp). The config file's reader and writer
// (room/src/match_config_json.cpp), the welcome's rows
// (protocol/src/control_tables.hpp) and client_part() are made from this one table.
#pragma once

#include <tuple>

#include "fts/sim/config.hpp"
#include "fts/sim/field_table.hpp"

namespace fts::sim {

// The kind of a field the welcome carries: lo..hi, what a reader of the welcome accepts.
struct ClientKey {
  double lo, hi;
};
// The kind of a field of the match alone.
struct HostOnly {};

template <class T>
constexpr fields::Field<MatchConfig, T, ClientKey> client_row(std::string_view key, T MatchConfig::*member, double lo,
                                                              double hi, fields::Presence presence) {
  return {key, member, {lo, hi}, presence};
}
template <class T>
constexpr fields::Field<MatchConfig, T, HostOnly> host_row(std::string_view key, T MatchConfig::*member) {
  return {key, member, {}, fields::Presence::required};
}

using fields::Presence;
// clang-format off
inline constexpr auto kMatchConfigFields = std::make_tuple(
    client_row("tick_rate_hz", &MatchConfig::tick_rate_hz, 1, 10000, Presence::required),
    client_row("model", &MatchConfig::model, 0, 2, Presence::nonzero),
    client_row("substeps", &MatchConfig::substeps, 1, 1024, Presence::nonzero),
    host_row("max_players", &MatchConfig::max_players),
    client_row("frame_s", &MatchConfig::frame_s, 1e-6, 1e6, Presence::required),
    client_row("arena_width_u", &MatchConfig::arena_width_u, 0, 1e6, Presence::required),
    client_row("arena_height_u", &MatchConfig::arena_height_u, 0, 1e6, Presence::required),
    host_row("spawn_margin_u", &MatchConfig::spawn_margin_u),
    host_row("spawn_gap_u", &MatchConfig::spawn_gap_u),
    host_row("spawn_attempts", &MatchConfig::spawn_attempts),
    client_row("friction_per_frame", &MatchConfig::friction_per_frame, 0, 1, Presence::nonzero),
    client_row("friction_cutoff_u_per_s", &MatchConfig::friction_cutoff_u_per_s, 0, 1e6, Presence::nonzero),
    host_row("radius_base_u", &MatchConfig::radius_base_u),
    host_row("radius_mass_divisor", &MatchConfig::radius_mass_divisor),
    host_row("player_mass", &MatchConfig::player_mass),
    host_row("player_vmax_u_per_s", &MatchConfig::player_vmax_u_per_s),
    host_row("player_accel_u_per_s2", &MatchConfig::player_accel_u_per_s2),
    host_row("player_lives", &MatchConfig::player_lives),
    host_row("player_coins", &MatchConfig::player_coins),
    host_row("player_multiplier", &MatchConfig::player_multiplier),
    host_row("respawn_delay_s", &MatchConfig::respawn_delay_s),
    host_row("player_spawn_x_fraction", &MatchConfig::player_spawn_x_fraction),
    host_row("spawn_protection_s", &MatchConfig::spawn_protection_s),
    host_row("late_join_share", &MatchConfig::late_join_share),
    host_row("enemies_max_normal", &MatchConfig::enemies_max_normal),
    host_row("enemies_min_late", &MatchConfig::enemies_min_late),
    host_row("boss_period", &MatchConfig::boss_period),
    host_row("boss_count", &MatchConfig::boss_count),
    host_row("boss_double_period", &MatchConfig::boss_double_period),
    host_row("boss_double_count", &MatchConfig::boss_double_count),
    host_row("swarm_phase", &MatchConfig::swarm_phase),
    host_row("swarm_count", &MatchConfig::swarm_count),
    host_row("enemies_cap", &MatchConfig::enemies_cap),
    host_row("chaser_index", &MatchConfig::chaser_index),
    host_row("level1_enemy_mass", &MatchConfig::level1_enemy_mass),
    host_row("normal_mass_base", &MatchConfig::normal_mass_base),
    host_row("normal_mass_per_level", &MatchConfig::normal_mass_per_level),
    host_row("normal_mass_per_q", &MatchConfig::normal_mass_per_q),
    host_row("normal_mass_jitter", &MatchConfig::normal_mass_jitter),
    host_row("normal_accel_base_u_per_frame2", &MatchConfig::normal_accel_base_u_per_frame2),
    host_row("normal_accel_per_level", &MatchConfig::normal_accel_per_level),
    host_row("normal_accel_per_q", &MatchConfig::normal_accel_per_q),
    host_row("normal_vmax_base_u_per_frame", &MatchConfig::normal_vmax_base_u_per_frame),
    host_row("normal_vmax_per_level", &MatchConfig::normal_vmax_per_level),
    host_row("normal_vmax_per_q", &MatchConfig::normal_vmax_per_q),
    host_row("swarm_mass_per_q1", &MatchConfig::swarm_mass_per_q1),
    host_row("swarm_radius_base_u", &MatchConfig::swarm_radius_base_u),
    host_row("swarm_radius_per_q", &MatchConfig::swarm_radius_per_q),
    host_row("swarm_vmax_base_u_per_frame", &MatchConfig::swarm_vmax_base_u_per_frame),
    host_row("swarm_vmax_per_level", &MatchConfig::swarm_vmax_per_level),
    host_row("swarm_vmax_per_q", &MatchConfig::swarm_vmax_per_q),
    host_row("swarm_accel_base_u_per_frame2", &MatchConfig::swarm_accel_base_u_per_frame2),
    host_row("swarm_accel_per_level", &MatchConfig::swarm_accel_per_level),
    host_row("swarm_accel_per_q", &MatchConfig::swarm_accel_per_q),
    host_row("boss_mass_per_q", &MatchConfig::boss_mass_per_q),
    host_row("boss_mass_per_pair", &MatchConfig::boss_mass_per_pair),
    host_row("boss_radius_base_u", &MatchConfig::boss_radius_base_u),
    host_row("boss_vmax_base_u_per_frame", &MatchConfig::boss_vmax_base_u_per_frame),
    host_row("boss_vmax_per_q", &MatchConfig::boss_vmax_per_q),
    host_row("boss_accel_base_u_per_frame2", &MatchConfig::boss_accel_base_u_per_frame2),
    host_row("boss_accel_per_q", &MatchConfig::boss_accel_per_q),
    host_row("goal_half_w_u", &MatchConfig::goal_half_w_u),
    host_row("goal_half_h_u", &MatchConfig::goal_half_h_u),
    host_row("goal_shrink_per_level_u", &MatchConfig::goal_shrink_per_level_u),
    host_row("goal_shrink_level_cap", &MatchConfig::goal_shrink_level_cap),
    host_row("boss_goal_half_w_u", &MatchConfig::boss_goal_half_w_u),
    host_row("boss_goal_half_h_u", &MatchConfig::boss_goal_half_h_u),
    host_row("goal_reach_u", &MatchConfig::goal_reach_u),
    host_row("reward_level_bonus", &MatchConfig::reward_level_bonus),
    host_row("credit_chain_s", &MatchConfig::credit_chain_s),
    client_row("bank_interest_factor", &MatchConfig::bank_interest_factor, 0, 1e6, Presence::required),
    host_row("level_multiplier_growth", &MatchConfig::level_multiplier_growth),
    host_row("level_life_price_growth", &MatchConfig::level_life_price_growth),
    host_row("price_mass", &MatchConfig::price_mass),
    host_row("price_mass_level_coeff", &MatchConfig::price_mass_level_coeff),
    host_row("price_mass_offset", &MatchConfig::price_mass_offset),
    host_row("price_speed", &MatchConfig::price_speed),
    host_row("price_speed_growth", &MatchConfig::price_speed_growth),
    host_row("speed_upgrade_factor", &MatchConfig::speed_upgrade_factor),
    host_row("price_accel", &MatchConfig::price_accel),
    host_row("price_accel_growth", &MatchConfig::price_accel_growth),
    host_row("accel_upgrade_factor", &MatchConfig::accel_upgrade_factor),
    host_row("price_rockets", &MatchConfig::price_rockets),
    host_row("price_life", &MatchConfig::price_life),
    host_row("price_life_growth", &MatchConfig::price_life_growth),
    host_row("price_multiplier", &MatchConfig::price_multiplier),
    host_row("price_multiplier_growth", &MatchConfig::price_multiplier_growth),
    client_row("multiplier_upgrade_factor", &MatchConfig::multiplier_upgrade_factor, 0, 1e6, Presence::required),
    host_row("price_bank", &MatchConfig::price_bank),
    host_row("shop_timeout_s", &MatchConfig::shop_timeout_s),
    host_row("lobby_timeout_s", &MatchConfig::lobby_timeout_s),
    host_row("rocket_cooldown_s", &MatchConfig::rocket_cooldown_s),
    host_row("rocket_mass", &MatchConfig::rocket_mass),
    host_row("rocket_radius_u", &MatchConfig::rocket_radius_u),
    host_row("rocket_speed_factor", &MatchConfig::rocket_speed_factor),
    host_row("rocket_lifetime_s", &MatchConfig::rocket_lifetime_s),
    host_row("coin_cap", &MatchConfig::coin_cap),
    host_row("multiplier_cap", &MatchConfig::multiplier_cap),
    host_row("player_vmax_cap_u_per_s", &MatchConfig::player_vmax_cap_u_per_s),
    host_row("player_accel_cap_u_per_s2", &MatchConfig::player_accel_cap_u_per_s2),
    host_row("player_mass_cap", &MatchConfig::player_mass_cap),
    host_row("lives_cap", &MatchConfig::lives_cap)
);
// clang-format on
// That every member has a row is checked once, in config_fields.cpp: the check costs
// about 7 s of compiling, which every file including this header would pay again.

template <class K>
inline constexpr bool is_client_key = std::is_same_v<std::remove_cvref_t<K>, ClientKey>;

// The fields a client needs (client_row above) copied from cfg, every other at its
// default: what the welcome carries, and all a client knows of the match's configuration.
MatchConfig client_part(const MatchConfig& cfg);

}  // namespace fts::sim
