#include <algorithm>
#include <cmath>

#include "fts/sim/collide.hpp"
#include "step_internal.hpp"

namespace fts::sim::detail {
namespace {

// Folds x into [lo, hi] as a ball reflecting off both walls would; returns the number
// of reflections (the velocity flips when it is odd).
double fold(double& x, double lo, double hi) {
  if (x >= lo && x <= hi) return 0.0;
  const double span = hi - lo;
  if (!(span > 0.0)) {  // the ball is as wide as the box: park it in the middle
    x = 0.5 * (lo + hi);
    return 1.0;
  }
  const double u = x - lo;
  const double crossings = std::fabs(std::floor(u / span));
  double m = std::fmod(u, 2.0 * span);  // exact
  if (m < 0.0) m += 2.0 * span;
  if (m > span) m = 2.0 * span - m;
  x = lo + m;
  return crossings;
}

}  // namespace

bool use_grid(const PhysicsSettings& s, std::size_t bodies) {
  switch (s.broadphase) {
    case Broadphase::pairs: return false;
    case Broadphase::grid: return true;
    case Broadphase::automatic: break;
  }
  return bodies > static_cast<std::size_t>(s.pairs_max_bodies);
}

namespace {

bool inside_walls(const Ball& b, const Arena& a) {
  return b.pos.x >= b.radius && b.pos.x <= a.width_u - b.radius && b.pos.y >= b.radius &&
         b.pos.y <= a.height_u - b.radius;
}

// A ball outside the walled box, folded back in (any number of reflections).
void fold_into_walls(Ball& b, const Arena& a, StepReport& report) {
  const double rx = fold(b.pos.x, b.radius, a.width_u - b.radius);
  const double ry = fold(b.pos.y, b.radius, a.height_u - b.radius);
  for (auto [n, v] : {std::pair{rx, &b.vel.x}, std::pair{ry, &b.vel.y}}) {
    if (n == 0.0) continue;
    report.wall_hits += static_cast<std::uint64_t>(std::min(n, 1e18));
    report.wall_impulse += 2.0 * b.mass * std::fabs(*v) * n;
    if (std::fmod(n, 2.0) == 1.0) *v = -*v;
  }
}

}  // namespace

void apply_boundary(World& world, StepReport& report) {
  const Arena& a = world.arena;
  if (a.boundary == Boundary::walls) {
    for (Ball& b : world.balls) {
      if (!inside_walls(b, a)) fold_into_walls(b, a, report);
    }
    return;
  }
  auto out = [&](const Ball& b) {
    const bool inside = b.pos.x >= 0.0 && b.pos.x <= a.width_u && b.pos.y >= 0.0 && b.pos.y <= a.height_u;
    if (!inside) report.fallen.push_back(b.id);
    return !inside;
  };
  world.balls.erase(std::remove_if(world.balls.begin(), world.balls.end(), out), world.balls.end());
}

void advance(World& world, double h, StepReport& report, DiscBounds* bounds, std::vector<std::uint32_t>& unsettled) {
  unsettled.clear();
  std::vector<Ball>& balls = world.balls;
  const Arena& a = world.arena;
  if (a.boundary != Boundary::walls) {
    for (Ball& b : balls) b.pos += b.vel * h;
    apply_boundary(world, report);
    if (bounds)
      for (const Ball& b : balls) bounds->add(b);
    return;
  }
  // Two loops, so the one without bounds does not test for them per ball; the bounds
  // are gathered in a local, which the compiler can keep in registers.
  const std::uint32_t n = static_cast<std::uint32_t>(balls.size());
  auto move = [&](std::uint32_t i) -> Ball& {
    Ball& b = balls[i];
    b.pos += b.vel * h;
    if (!inside_walls(b, a)) {
      fold_into_walls(b, a, report);
      if (!inside_walls(b, a)) unsettled.push_back(i);  // rounding: settle() folds it again
    }
    return b;
  };
  if (!bounds) {
    for (std::uint32_t i = 0; i < n; ++i) move(i);
    return;
  }
  DiscBounds local;
  for (std::uint32_t i = 0; i < n; ++i) local.add(move(i));
  *bounds = local;
}

void settle(World& world, std::vector<std::uint32_t>& unsettled, StepReport& report) {
  const Arena& a = world.arena;
  if (a.boundary != Boundary::walls) {
    apply_boundary(world, report);
    return;
  }
  // Few balls (the game: tens) are cheaper to pass over than to sort; both visit the
  // moved balls in index order, so the results are the same.
  if (unsettled.size() * 8 >= world.balls.size()) {
    apply_boundary(world, report);
    return;
  }
  std::sort(unsettled.begin(), unsettled.end());
  unsettled.erase(std::unique(unsettled.begin(), unsettled.end()), unsettled.end());
  for (std::uint32_t i : unsettled) {
    Ball& b = world.balls[i];
    if (!inside_walls(b, a)) fold_into_walls(b, a, report);
  }
}

void find_overlaps(const std::vector<Ball>& balls, bool grid_mode, DiscGrid& grid, std::vector<IndexPair>& out,
                   const DiscBounds* bounds) {
  out.clear();
  const std::uint32_t n = static_cast<std::uint32_t>(balls.size());
  auto test = [&](std::uint32_t i, std::uint32_t j) {
    const double reach = balls[i].radius + balls[j].radius;
    if (length_sq(balls[j].pos - balls[i].pos) <= reach * reach) out.emplace_back(i, j);
  };
  if (!grid_mode) {
    for (std::uint32_t i = 0; i < n; ++i)
      for (std::uint32_t j = i + 1; j < n; ++j) test(i, j);
    return;
  }
  grid.touching_pairs(balls, out, bounds);
  std::sort(out.begin(), out.end());
}

void step_seed(World& world, const PhysicsSettings& s, double dt, StepReport& report) {
  DiscGrid& grid = world.buffers.discs;
  std::vector<IndexPair>& pairs = world.buffers.pairs;
  std::vector<std::uint32_t>& unsettled = world.buffers.unsettled;
  auto& balls = world.balls;
  const bool grid_mode = use_grid(s, balls.size());
  DiscBounds bounds;
  advance(world, dt, report, grid_mode ? &bounds : nullptr, unsettled);
  find_overlaps(balls, grid_mode, grid, pairs, &bounds);
  for (auto [i, j] : pairs) {
    Ball& b1 = balls[i];
    Ball& b2 = balls[j];
    const double reach = b1.radius + b2.radius;
    if (length_sq(b2.pos - b1.pos) > reach * reach) continue;  // an earlier push moved them
    // The seed moves b1; an immovable b1 (mass +inf) stays and b2 moves instead.
    const bool fixed1 = std::isinf(b1.mass), fixed2 = std::isinf(b2.mass);
    if (fixed1 && fixed2) continue;
    if (fixed1) push_apart_seed(b2, b1);
    else push_apart_seed(b1, b2);
    respond_seed(b1, b2);
    ++report.collisions;
    report.contacts.push_back({b1.id, b2.id});
    unsettled.push_back(i);
    unsettled.push_back(j);
  }
  // A push-apart can cross an edge: fold the moved balls again so nothing ends outside.
  settle(world, unsettled, report);
}

void step_discrete(World& world, const PhysicsSettings& s, double dt, StepReport& report) {
  const int k = std::max(1, s.substeps);
  const double h = dt / k;
  DiscGrid& grid = world.buffers.discs;
  std::vector<IndexPair>& pairs = world.buffers.pairs;
  std::vector<std::uint32_t>& unsettled = world.buffers.unsettled;
  auto& balls = world.balls;
  for (int sub = 0; sub < k; ++sub) {
    const bool grid_mode = use_grid(s, balls.size());
    DiscBounds bounds;
    advance(world, h, report, grid_mode ? &bounds : nullptr, unsettled);
    find_overlaps(balls, grid_mode, grid, pairs, &bounds);
    for (auto [i, j] : pairs) {
      Ball& a = balls[i];
      Ball& b = balls[j];
      const Vec2 d = b.pos - a.pos;
      const double reach = a.radius + b.radius;
      const double dist_sq = length_sq(d);
      if (dist_sq > reach * reach) continue;
      const double dist = std::sqrt(dist_sq);
      separate(a, b, unit_normal(d, dist), reach - dist);
      unsettled.push_back(i);
      unsettled.push_back(j);
      if (respond_elastic(a, b, contact_direction(a, b))) {
        ++report.collisions;
        report.contacts.push_back({a.id, b.id});
      }
    }
    if (!pairs.empty()) settle(world, unsettled, report);
  }
}

}  // namespace fts::sim::detail
