// The physics world and its step: three collision models from literal to exact.
// Pure: no clock, no I/O, no globals; iteration is by ball order (ascending id).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "fts/sim/ball.hpp"
#include "fts/sim/step_buffers.hpp"

namespace fts::sim {

enum class Model : std::uint8_t {
  seed,        // the slides literally: axis push-apart, trigonometric response
  discrete,    // vector form, push-apart along the normal, K sub-steps per tick
  continuous,  // exact times of impact inside the tick, processed in time order
};
enum class Boundary : std::uint8_t {
  open,   // a ball whose centre leaves the rectangle falls off and is removed
  walls,  // reflecting walls at the rectangle's edges
};
enum class Broadphase : std::uint8_t { automatic, pairs, grid };

std::string_view to_string(Model m);
std::string_view to_string(Boundary b);
std::string_view to_string(Broadphase b);
std::optional<Model> parse_model(std::string_view s);
std::optional<Boundary> parse_boundary(std::string_view s);
std::optional<Broadphase> parse_broadphase(std::string_view s);

struct Arena {
  double width_u = 500.0;
  double height_u = 300.0;
  Boundary boundary = Boundary::open;
};

// What a scene declares; the engine pays only for what is switched on.
struct PhysicsSettings {
  Model model = Model::continuous;
  int substeps = 1;                    // discrete only: sub-steps per tick
  Broadphase broadphase = Broadphase::automatic;
  int pairs_max_bodies = 64;           // automatic: all pairs up to this many bodies
  bool friction = false;               // the game's velocity decay
  double friction_per_frame = 0.991;   // velocity factor per frame of frame_s
  double frame_s = 0.01;               // the original's frame (GAME_RULES.md "Units")
  double friction_cutoff_u_per_s = 1.0;  // a slower, unthrusted component stops
};

struct Contact {
  BallId a = 0;  // a < b
  BallId b = 0;
};

// Everything one step did; cleared by step().
struct StepReport {
  std::uint64_t collisions = 0;   // ball-ball impulses applied
  std::uint64_t wall_hits = 0;
  double wall_impulse = 0.0;      // sum of |dp| given to walls
  std::uint64_t event_cap_hits = 0;  // continuous: ticks cut short by the event budget
  std::vector<Contact> contacts;  // every touching pair, in processing order
  std::vector<BallId> fallen;     // removed off an open edge, in id order
};

struct World {
  Arena arena;
  std::vector<Ball> balls;  // kept sorted by id
  StepBuffers buffers;      // the step's working memory (not state; never copied)
};

// Precomputed per-tick constants (friction factor without libm pow).
struct StepConstants {
  double dt_s = 0.01;
  double friction_factor = 1.0;  // friction_per_frame^(dt_s / frame_s), or 1 without friction
};
StepConstants make_step_constants(const PhysicsSettings& settings, double dt_s);

// Advances the world by one tick of dt_s seconds: the model moves the balls and applies
// the impulses, then every body's velocity is integrated once (friction, thrust flags
// cleared).
void step(World& world, const PhysicsSettings& settings, const StepConstants& k, StepReport& report);

// Measurements (pure reads).
double kinetic_energy(const std::vector<Ball>& balls);
Vec2 momentum(const std::vector<Ball>& balls);
std::uint64_t state_hash(const std::vector<Ball>& balls);
// Largest overlap r1 + r2 - d over all pairs (0 when none), via the grid.
double max_penetration(const std::vector<Ball>& balls);
// Balls whose centre is outside a walled arena.
std::uint64_t count_escaped(const World& world);
bool all_finite(const std::vector<Ball>& balls);

}  // namespace fts::sim
