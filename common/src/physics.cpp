#include "fts/sim/physics.hpp"

#include <algorithm>
#include <cmath>

#include "fts/sim/detmath.hpp"
#include "fts/sim/hash.hpp"
#include "step_internal.hpp"

namespace fts::sim {

std::string_view to_string(Model m) {
  switch (m) {
    case Model::seed: return "seed";
    case Model::discrete: return "discrete";
    case Model::continuous: return "continuous";
  }
  return "?";
}
std::string_view to_string(Boundary b) { return b == Boundary::open ? "open" : "walls"; }
std::string_view to_string(Broadphase b) {
  switch (b) {
    case Broadphase::automatic: return "auto";
    case Broadphase::pairs: return "pairs";
    case Broadphase::grid: return "grid";
  }
  return "?";
}
std::optional<Model> parse_model(std::string_view s) {
  if (s == "seed") return Model::seed;
  if (s == "discrete") return Model::discrete;
  if (s == "continuous") return Model::continuous;
  return std::nullopt;
}
std::optional<Boundary> parse_boundary(std::string_view s) {
  if (s == "open") return Boundary::open;
  if (s == "walls") return Boundary::walls;
  return std::nullopt;
}
std::optional<Broadphase> parse_broadphase(std::string_view s) {
  if (s == "auto") return Broadphase::automatic;
  if (s == "pairs") return Broadphase::pairs;
  if (s == "grid") return Broadphase::grid;
  return std::nullopt;
}

StepConstants make_step_constants(const PhysicsSettings& settings, double dt_s) {
  StepConstants k;
  k.dt_s = dt_s;
  // 0.991 per frame becomes 0.991^(dt / frame) per tick, without libm's pow.
  k.friction_factor = settings.friction ? det_pow(settings.friction_per_frame, dt_s / settings.frame_s) : 1.0;
  return k;
}

namespace {

// The one velocity integration of a tick, once per body: friction decays the velocity
// and stops a slow component unless that axis was thrust this tick (Box2D v3 applies
// its damping in the same place, per body, in the velocity integration). It runs after
// the model's moves and impulses, so friction of tick t lands between the impulses of
// t and the thrust of t+1, which is where the game has always applied it.
void integrate_velocities(std::vector<Ball>& balls, const PhysicsSettings& settings, const StepConstants& k) {
  if (!settings.friction) {
    for (Ball& b : balls) b.thrust_axes = 0;
    return;
  }
  const double cut = settings.friction_cutoff_u_per_s;
  for (Ball& b : balls) {
    b.vel *= k.friction_factor;
    if (!(b.thrust_axes & kThrustX) && std::fabs(b.vel.x) < cut) b.vel.x = 0.0;
    if (!(b.thrust_axes & kThrustY) && std::fabs(b.vel.y) < cut) b.vel.y = 0.0;
    b.thrust_axes = 0;
  }
}

}  // namespace

void step(World& world, const PhysicsSettings& settings, const StepConstants& k, StepReport& report) {
  report.collisions = 0;
  report.wall_hits = 0;
  report.wall_impulse = 0.0;
  report.event_cap_hits = 0;
  report.contacts.clear();
  report.fallen.clear();
  switch (settings.model) {
    case Model::seed: detail::step_seed(world, settings, k.dt_s, report); break;
    case Model::discrete: detail::step_discrete(world, settings, k.dt_s, report); break;
    case Model::continuous: detail::step_continuous(world, settings, k.dt_s, report); break;
  }
  integrate_velocities(world.balls, settings, k);
  std::sort(report.fallen.begin(), report.fallen.end());
}

double kinetic_energy(const std::vector<Ball>& balls) {
  double e = 0.0;
  for (const Ball& b : balls) e += 0.5 * b.mass * length_sq(b.vel);
  return e;
}

Vec2 momentum(const std::vector<Ball>& balls) {
  Vec2 p;
  for (const Ball& b : balls) p += b.vel * b.mass;
  return p;
}

std::uint64_t state_hash(const std::vector<Ball>& balls) {
  Hasher h;
  h.add_u64(balls.size());
  for (const Ball& b : balls) {
    h.add_u64(b.id.value);
    h.add_double(b.pos.x);
    h.add_double(b.pos.y);
    h.add_double(b.vel.x);
    h.add_double(b.vel.y);
    h.add_double(b.radius);
    h.add_double(b.mass);
  }
  return h.value();
}

double max_penetration(const std::vector<Ball>& balls) {
  DiscGrid grid;
  std::vector<detail::IndexPair> pairs;
  detail::find_overlaps(balls, balls.size() > 64, grid, pairs);
  double worst = 0.0;
  for (auto [i, j] : pairs) {
    const double d = length(balls[j].pos - balls[i].pos);
    worst = std::max(worst, balls[i].radius + balls[j].radius - d);
  }
  return worst;
}

std::uint64_t count_escaped(const World& world) {
  if (world.arena.boundary != Boundary::walls) return 0;
  std::uint64_t n = 0;
  for (const Ball& b : world.balls) {
    if (!(b.pos.x >= 0.0 && b.pos.x <= world.arena.width_u && b.pos.y >= 0.0 &&
          b.pos.y <= world.arena.height_u))
      ++n;
  }
  return n;
}

bool all_finite(const std::vector<Ball>& balls) {
  return std::all_of(balls.begin(), balls.end(), [](const Ball& b) {
    return is_finite(b.pos) && is_finite(b.vel) && std::isfinite(b.radius) && std::isfinite(b.mass);
  });
}

}  // namespace fts::sim
