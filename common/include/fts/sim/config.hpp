// MatchConfig: every number of GAME_RULES.md as a default, with units in the names.
// Every member is listed once in config_fields.hpp, which says whether a client needs it.
// "per frame" figures of the original (frame = 0.01 s) are kept in their original unit
// where the rules state a formula in that unit (enemy speeds) and converted in code.
#pragma once

#include <cstdint>
#include <string>

#include "fts/sim/physics.hpp"

namespace fts::sim {

struct MatchConfig {
  // Simulation.
  double tick_rate_hz = 100.0;
  Model model = Model::continuous;
  int substeps = 1;  // discrete model only
  std::int64_t max_players = 8;
  double frame_s = 0.01;  // the original's frame, for "per frame" figures

  // Platform.
  double arena_width_u = 500.0;
  double arena_height_u = 300.0;
  double spawn_margin_u = 50.0;   // enemies spawn in [margin, W-margin] x [margin, H-margin]
  double spawn_gap_u = 5.0;       // free space kept between a spawned ball and others
  std::int64_t spawn_attempts = 2000;  // redraws before a fallback (see level.cpp)

  // Friction: factor per original frame; a slower, unthrusted component stops.
  double friction_per_frame = 0.991;
  double friction_cutoff_u_per_s = 1.0;

  // Balls: r = radius_base + floor(mass / radius_mass_divisor).
  double radius_base_u = 11.0;
  double radius_mass_divisor = 8.0;

  // Player start.
  std::int64_t player_mass = 40;
  double player_vmax_u_per_s = 170.0;
  double player_accel_u_per_s2 = 200.0;
  std::int64_t player_lives = 3;
  std::int64_t player_coins = 0;
  double player_multiplier = 1.0;
  double respawn_delay_s = 2.0;
  double player_spawn_x_fraction = 1.0 / 6.0;  // spawn column, in the left third

  // A ball put on the platform (every level start, a restart included, and every
  // respawn or arrival during a level) is immovable (others reflect off it, its touches
  // credit nobody) until spawn_protection_s after, or until its player thrusts or fires.
  // A player joining a running match gets every cleared level's growth
  // (multiplier, life price) and late_join_share of the median total value (coins +
  // spent) of the players still in the match, if that is more than the start coins.
  // Respawns and late joiners (README, "Where the rules left room")
  double spawn_protection_s = 3.0;  // immovable this long after a (re)spawn, or until the player acts; 0: off
  double late_join_share = 1.0;     // of the median total value, for a newcomer; 0: the original start

  // Levels: n(L).
  std::int64_t enemies_max_normal = 7;       // n = L capped by 7 - floor(L/10)
  std::int64_t enemies_min_late = 5;         // if n < 5 and L > 5 then n = 5
  std::int64_t boss_period = 10;             // L mod 10 = 0: boss level
  std::int64_t boss_count = 1;
  std::int64_t boss_double_period = 20;      // L mod 20 = 0: two bosses
  std::int64_t boss_double_count = 2;
  std::int64_t swarm_phase = 5;              // L mod 10 = 5: swarm level
  std::int64_t swarm_count = 12;
  std::int64_t enemies_cap = 48;             // n(L) * players, capped
  std::int64_t chaser_index = 3;             // the fourth enemy chases
  double level1_enemy_mass = 30.0;           // level 1: one still enemy at the centre

  // Normal enemy: mass 28 + floor(2.1 L) + 8q + j, j = U(1..4) * U(-1..1).
  double normal_mass_base = 28.0;
  double normal_mass_per_level = 2.1;
  double normal_mass_per_q = 8.0;
  std::int64_t normal_mass_jitter = 4;
  double normal_accel_base_u_per_frame2 = 0.009;
  double normal_accel_per_level = 0.00065;
  double normal_accel_per_q = -0.0007;
  double normal_vmax_base_u_per_frame = 1.1;
  double normal_vmax_per_level = 0.11;
  double normal_vmax_per_q = -0.1;

  // Swarm enemy.
  double swarm_mass_per_q1 = 20.0;  // mass 20 (q + 1)
  double swarm_radius_base_u = 13.0;
  double swarm_radius_per_q = 1.8;
  double swarm_vmax_base_u_per_frame = 0.85;
  double swarm_vmax_per_level = 0.09;
  double swarm_vmax_per_q = -0.09;
  double swarm_accel_base_u_per_frame2 = 0.0075;
  double swarm_accel_per_level = 0.00065;
  double swarm_accel_per_q = -0.0007;

  // Boss: mass 100 q - 100 floor((L - 10) / 20), radius 15 + floor(mass / 8).
  double boss_mass_per_q = 100.0;
  double boss_mass_per_pair = 100.0;
  double boss_radius_base_u = 15.0;
  double boss_vmax_base_u_per_frame = 1.7;
  double boss_vmax_per_q = 0.08;
  double boss_accel_base_u_per_frame2 = 0.01;
  double boss_accel_per_q = 0.0002;

  // Enemy behaviour.
  double goal_half_w_u = 150.0;  // goal box half-size (150 - 2l) x (100 - 2l), l = min(L, 30)
  double goal_half_h_u = 100.0;
  double goal_shrink_per_level_u = 2.0;
  std::int64_t goal_shrink_level_cap = 30;
  double boss_goal_half_w_u = 90.0;
  double boss_goal_half_h_u = 45.0;
  double goal_reach_u = 3.0;

  // Coins and credit.
  std::int64_t reward_level_bonus = 5;  // floor(mass x multiplier) + L + 5
  double credit_chain_s = 5.0;
  double bank_interest_factor = 1.1;
  double level_multiplier_growth = 1.02;
  double level_life_price_growth = 1.015;

  // Shop: start prices and price rules.
  std::int64_t price_mass = 35;
  double price_mass_level_coeff = 0.55;  // floor(price + 0.55 L - 1)
  double price_mass_offset = 1.0;
  std::int64_t price_speed = 100;
  double price_speed_growth = 1.2;
  double speed_upgrade_factor = 1.05;
  std::int64_t price_accel = 150;
  double price_accel_growth = 1.2;
  double accel_upgrade_factor = 1.05;
  std::int64_t price_rockets = 1'000'000;
  std::int64_t price_life = 500;
  double price_life_growth = 1.1;
  std::int64_t price_multiplier = 100;
  double price_multiplier_growth = 1.5;
  double multiplier_upgrade_factor = 1.1;
  std::int64_t price_bank = 500;
  double shop_timeout_s = 30.0;
  // The lobby starts the match when every connected player is ready, or this long after
  // the first one became ready (an idle player does not hold the others for ever).
  double lobby_timeout_s = 30.0;

  // Rockets.
  double rocket_cooldown_s = 1.0;
  double rocket_mass = 5.0;
  double rocket_radius_u = 3.0;
  double rocket_speed_factor = 10.0;  // x the player's vmax
  double rocket_lifetime_s = 3.0;

  // Caps that keep the economy defined at the extremes (saturating, never overflow).
  std::int64_t coin_cap = 1'000'000'000'000'000;  // 10^15: exact in a double
  double multiplier_cap = 1e9;
  double player_vmax_cap_u_per_s = 5000.0;
  double player_accel_cap_u_per_s2 = 100000.0;
  std::int64_t player_mass_cap = 100000;
  std::int64_t lives_cap = 1'000'000;

  bool operator==(const MatchConfig&) const = default;
};

// Whole ticks for a duration at the configured tick rate (at least 1).
std::int64_t ticks_for(const MatchConfig& cfg, double seconds);
// Radius of an ordinary ball of this mass: 11 + floor(mass / 8).
double radius_for_mass(const MatchConfig& cfg, double mass);
// Physics settings of the game: the configured model and the game's friction (per frame
// of frame_s; an axis the match thrusts this tick is spared the cut-off, see
// Ball::thrust_axes).
PhysicsSettings physics_settings(const MatchConfig& cfg);
// Empty when valid, else a message naming the first bad field.
std::string validate(const MatchConfig& cfg);

}  // namespace fts::sim
