// Runs a physics scene for N ticks and measures it (fts-sim's scene mode).
#pragma once

#include <cstdint>
#include <string>

#include "fts/sim/scene.hpp"

namespace fts::simtool {

struct SceneReport {
  std::string model;
  double tick_rate_hz = 0;
  int substeps = 1;
  std::int64_t steps = 0;
  std::string broadphase;
  std::uint64_t bodies_start = 0, bodies_end = 0;
  double wall_seconds = 0, ns_per_body_step = 0;
  double kinetic_energy_start = 0, kinetic_energy_end = 0, energy_drift_max_rel = 0;
  sim::Vec2 momentum_start, momentum_end;
  std::uint64_t collisions = 0, wall_hits = 0, fallen = 0, escaped = 0, event_cap_hits = 0;
  double wall_impulse = 0, max_penetration = 0;
  bool finite = true;
  std::uint64_t state_hash = 0;
};

// Steps `world` `scene.steps` times with the scene's settings. Only the steps are timed;
// measurements run between them. Penetration is sampled every `check_every` ticks.
SceneReport run_scene(const sim::Scene& scene, sim::World& world, std::int64_t check_every = 1);

std::string to_json(const SceneReport& r);

}  // namespace fts::simtool
