// A physics scene: arena, settings, explicit balls and random generators. Pure data
// plus a deterministic builder; reading it from JSON lives outside common/.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fts/sim/broadphase.hpp"
#include "fts/sim/physics.hpp"

namespace fts::sim {

struct BallSpec {
  double x = 0, y = 0, vx = 0, vy = 0, r = 1, m = 1;
};

// `count` balls of one size placed uniformly at random without overlap (unless
// allow_overlap) inside `region` (default: the whole arena), moving at `speed` in
// uniformly random directions.
struct Generator {
  std::int64_t count = 0;
  double radius = 1.0;
  double mass = 1.0;
  double speed_u_per_s = 0.0;
  std::uint64_t seed = 1;
  std::optional<Box> region;
  bool allow_overlap = false;
};

struct Scene {
  double tick_rate_hz = 100.0;
  std::int64_t steps = 1000;
  Arena arena;
  PhysicsSettings physics;
  std::vector<BallSpec> balls;
  std::vector<Generator> generators;
};

// Builds the initial world (ids 1, 2, ... in order: explicit balls, then generators).
// Returns an error message naming the generator when placement is impossible.
std::optional<std::string> build_world(const Scene& scene, World& out);

}  // namespace fts::sim
