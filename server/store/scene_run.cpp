#include "store/scene_run.hpp"

#include <chrono>
#include <cmath>

#include <nlohmann/json.hpp>

#include "fts/room/text.hpp"

namespace fts::simtool {

SceneReport run_scene(const sim::Scene& scene, sim::World& world, std::int64_t check_every) {
  SceneReport r;
  r.model = std::string(sim::to_string(scene.physics.model));
  r.tick_rate_hz = scene.tick_rate_hz;
  r.substeps = scene.physics.substeps;
  r.steps = scene.steps;
  r.broadphase = std::string(sim::to_string(scene.physics.broadphase));
  r.bodies_start = world.balls.size();
  r.kinetic_energy_start = sim::kinetic_energy(world.balls);
  r.momentum_start = sim::momentum(world.balls);
  const double e0 = r.kinetic_energy_start;
  const double dt = 1.0 / scene.tick_rate_hz;
  const sim::StepConstants k = sim::make_step_constants(scene.physics, dt);
  sim::StepReport step;
  std::uint64_t body_steps = 0;
  std::chrono::steady_clock::duration elapsed{};
  for (std::int64_t t = 0; t < scene.steps; ++t) {
    body_steps += world.balls.size();
    const auto start = std::chrono::steady_clock::now();
    sim::step(world, scene.physics, k, step);
    elapsed += std::chrono::steady_clock::now() - start;
    r.collisions += step.collisions;
    r.wall_hits += step.wall_hits;
    r.wall_impulse += step.wall_impulse;
    r.fallen += step.fallen.size();
    r.event_cap_hits += step.event_cap_hits;
    if (e0 > 0.0) {
      const double drift = std::fabs(sim::kinetic_energy(world.balls) - e0) / e0;
      if (!(drift <= r.energy_drift_max_rel)) r.energy_drift_max_rel = drift;  // NaN sticks
    }
    if (check_every > 0 && (t % check_every == 0 || t + 1 == scene.steps)) {
      const double pen = sim::max_penetration(world.balls);
      if (pen > r.max_penetration) r.max_penetration = pen;
      r.escaped = std::max(r.escaped, sim::count_escaped(world));
      r.finite = r.finite && sim::all_finite(world.balls);
    }
  }
  r.wall_seconds = std::chrono::duration<double>(elapsed).count();
  r.ns_per_body_step = body_steps ? r.wall_seconds * 1e9 / static_cast<double>(body_steps) : 0.0;
  r.bodies_end = world.balls.size();
  r.kinetic_energy_end = sim::kinetic_energy(world.balls);
  r.momentum_end = sim::momentum(world.balls);
  r.escaped = std::max(r.escaped, sim::count_escaped(world));
  r.finite = r.finite && sim::all_finite(world.balls);
  r.state_hash = sim::state_hash(world.balls);
  return r;
}

std::string to_json(const SceneReport& r) {
  nlohmann::ordered_json j;
  j["model"] = r.model;
  j["tick_rate"] = r.tick_rate_hz;
  j["substeps"] = r.substeps;
  j["steps"] = r.steps;
  j["broadphase"] = r.broadphase;
  j["bodies_start"] = r.bodies_start;
  j["bodies_end"] = r.bodies_end;
  j["wall_seconds"] = r.wall_seconds;
  j["ns_per_body_step"] = r.ns_per_body_step;
  j["kinetic_energy_start"] = r.kinetic_energy_start;
  j["kinetic_energy_end"] = r.kinetic_energy_end;
  j["energy_drift_max_rel"] = r.energy_drift_max_rel;
  j["momentum_start"] = {r.momentum_start.x, r.momentum_start.y};
  j["momentum_end"] = {r.momentum_end.x, r.momentum_end.y};
  j["collisions"] = r.collisions;
  j["wall_hits"] = r.wall_hits;
  j["wall_impulse"] = r.wall_impulse;
  j["fallen"] = r.fallen;
  j["escaped"] = r.escaped;
  j["max_penetration"] = r.max_penetration;
  j["event_cap_hits"] = r.event_cap_hits;
  j["all_finite"] = r.finite;
  j["state_hash"] = room::hex16(r.state_hash);
  return j.dump();
}

}  // namespace fts::simtool
