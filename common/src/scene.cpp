#include "fts/sim/scene.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "fts/sim/rng.hpp"

namespace fts::sim {
namespace {

// Spatial hash for placement checks; an ordered map keeps it deterministic and
// unbounded in extent (generation is not a hot path).
class PlacementIndex {
 public:
  explicit PlacementIndex(double cell) : cell_(cell > 0 ? cell : 1.0) {}

  bool fits(const std::vector<Ball>& balls, Vec2 p, double r) const {
    const auto [cx, cy] = key(p);
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        auto it = cells_.find({cx + dx, cy + dy});
        if (it == cells_.end()) continue;
        for (std::uint32_t i : it->second) {
          const double reach = balls[i].radius + r;
          if (length_sq(balls[i].pos - p) < reach * reach) return false;
        }
      }
    }
    return true;
  }
  void add(std::uint32_t index, Vec2 p) { cells_[key(p)].push_back(index); }

 private:
  std::pair<std::int64_t, std::int64_t> key(Vec2 p) const {
    auto k = [&](double v) {
      const double c = std::floor(v / cell_);
      return static_cast<std::int64_t>(std::clamp(c, -4e18, 4e18));
    };
    return {k(p.x), k(p.y)};
  }
  double cell_;
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::uint32_t>> cells_;
};

Vec2 random_direction(Rng& rng) {
  // Rejection sampling in the unit disc: uniform angle without sin/cos.
  for (;;) {
    const Vec2 d{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)};
    const double l2 = length_sq(d);
    if (l2 > 1e-12 && l2 <= 1.0) return d * (1.0 / std::sqrt(l2));
  }
}

}  // namespace

std::optional<std::string> build_world(const Scene& scene, World& out) {
  out.arena = scene.arena;
  out.balls.clear();
  double rmax = 0.0;
  for (const BallSpec& b : scene.balls) rmax = std::max(rmax, b.r);
  for (const Generator& g : scene.generators) rmax = std::max(rmax, g.radius);
  PlacementIndex index(2.0 * rmax);
  std::uint32_t next_id = 1;
  for (const BallSpec& s : scene.balls) {
    const auto i = static_cast<std::uint32_t>(out.balls.size());
    out.balls.push_back({next_id++, {s.x, s.y}, {s.vx, s.vy}, s.r, s.m});
    index.add(i, {s.x, s.y});
  }
  for (std::size_t gi = 0; gi < scene.generators.size(); ++gi) {
    const Generator& g = scene.generators[gi];
    Rng rng(g.seed);
    const Box region = g.region.value_or(Box{0.0, 0.0, scene.arena.width_u, scene.arena.height_u});
    // Centres keep a radius from the region's edges.
    const double x0 = region.x0 + g.radius, x1 = region.x1 - g.radius;
    const double y0 = region.y0 + g.radius, y1 = region.y1 - g.radius;
    if (!(x0 <= x1 && y0 <= y1)) {
      return "generators[" + std::to_string(gi) + "]: region too small for radius " + std::to_string(g.radius);
    }
    constexpr int kAttempts = 100000;
    for (std::int64_t k = 0; k < g.count; ++k) {
      bool placed = false;
      for (int attempt = 0; attempt < kAttempts && !placed; ++attempt) {
        const Vec2 p{rng.uniform(x0, x1), rng.uniform(y0, y1)};
        if (!g.allow_overlap && !index.fits(out.balls, p, g.radius)) continue;
        const auto i = static_cast<std::uint32_t>(out.balls.size());
        out.balls.push_back({next_id++, p, random_direction(rng) * g.speed_u_per_s, g.radius, g.mass});
        index.add(i, p);
        placed = true;
      }
      if (!placed) {
        return "generators[" + std::to_string(gi) + "]: impossible placement: could not place ball " +
               std::to_string(k + 1) + " of " + std::to_string(g.count) + " without overlap after " +
               std::to_string(kAttempts) + " attempts (count too high for the region?)";
      }
    }
  }
  return std::nullopt;
}

}  // namespace fts::sim
