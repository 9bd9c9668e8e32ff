// Small builders shared by the physics tests.
#pragma once

#include <initializer_list>

#include "fts/sim/physics.hpp"

namespace fts::test {

inline sim::Ball ball(sim::BallId id, double x, double y, double vx, double vy, double r, double m) {
  return sim::Ball{id, {x, y}, {vx, vy}, r, m};
}

inline sim::World walled(double w, double h, std::initializer_list<sim::Ball> balls) {
  sim::World world;
  world.arena = {w, h, sim::Boundary::walls};
  world.balls = balls;
  return world;
}

inline sim::PhysicsSettings settings(sim::Model model, int substeps = 1) {
  sim::PhysicsSettings s;
  s.model = model;
  s.substeps = substeps;
  return s;
}

// Steps `world` n ticks at dt; returns the total ball-ball collisions.
inline std::uint64_t run(sim::World& world, const sim::PhysicsSettings& s, double dt, long n,
                         double* max_pen = nullptr) {
  const auto k = sim::make_step_constants(s, dt);
  sim::StepReport rep;
  std::uint64_t hits = 0;
  for (long i = 0; i < n; ++i) {
    sim::step(world, s, k, rep);
    hits += rep.collisions;
    if (max_pen) {
      const double p = sim::max_penetration(world.balls);
      if (p > *max_pen) *max_pen = p;
    }
  }
  return hits;
}

constexpr sim::Model kAllModels[] = {sim::Model::seed, sim::Model::discrete, sim::Model::continuous};

}  // namespace fts::test
