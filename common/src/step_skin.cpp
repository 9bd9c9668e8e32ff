// The continuous model's skin (see step_continuous.cpp): each ball's position when it
// was built, the pairs of balls that can meet while both stay within half_skin of it,
// and the same pairs per ball. Built when step_continuous finds it no longer fits.
#include <cmath>

#include "step_internal.hpp"

namespace fts::sim::detail {
namespace {

// Half the skin, in rms travels per tick plus mean radii (cost only). callgrind,
// gas-10000 continuous, 50 ticks, instructions by kSkinTravels, before predictions were
// kept across ticks: 3: 249 M, 4: 212 M, 6: 207 M, 8: ~230 M, 12: 271 M, 20: 390 M
// (wider skins list more pairs to predict every tick; narrower ones rebuild more
// often); with them: 6: 160 M, 8: 154 M, 10: 154 M, 12: 153 M, 14: 158 M, 20: 177 M.
constexpr double kSkinTravels = 10.0;
constexpr double kSkinRadii = 0.05;

}  // namespace

void build_continuous_skin(const std::vector<Ball>& balls, double dt, StepBuffers& skin) {
  const std::uint32_t n = static_cast<std::uint32_t>(balls.size());
  Grid& grid = skin.grid;
  // Half the skin: a few ticks of the typical (rms) travel plus a little of the mean
  // radius, so a ball at a typical speed keeps its skin for several ticks while the
  // boxes stay small. Only the cost depends on it.
  double travel_sq = 0.0, radius_sum = 0.0;
  for (const Ball& b : balls) {
    travel_sq += length_sq(b.vel) * dt * dt;
    radius_sum += b.radius;
  }
  const double inv_n = 1.0 / static_cast<double>(n);
  double h = kSkinTravels * std::sqrt(travel_sq * inv_n) + kSkinRadii * radius_sum * inv_n;
  if (!(h > 0.0) || !std::isfinite(h)) h = 0.0;
  skin.half_skin = h;
  skin.skin_origin.resize(n);
  skin.skin_id.resize(n);
  BigVector<Box>& boxes = grid.boxes();
  boxes.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const Ball& b = balls[i];
    skin.skin_origin[i] = b.pos;
    skin.skin_id[i] = b.id.value;
    const double m = b.radius + h;
    boxes[i] = {b.pos.x - m, b.pos.y - m, b.pos.x + m, b.pos.y + m};
  }
  grid.build();
  auto& pairs = skin.skin_pairs;
  // Two balls each within half_skin of their origins can touch only if their origins
  // are within r_i + r_j + 2 half_skin: a disc test, tighter than the boxes' (about a
  // fifth fewer pairs to predict every tick). The box is the ball's disc of that reach,
  // so the grid's scan tests the discs itself, from the slots it reads anyway (a pass
  // over the pairs reading the origins at random cost more than the scan at 10^5). The
  // rounding of centres taken from boxes (1e-13 u) is far inside the 1 % of half_skin
  // that in_skin keeps in hand.
  grid.overlapping_disc_pairs(pairs);
  // Per ball, the same pairs (a counting sort into CSR), each ball's list ended by
  // kEndOfNear; the pairs put in order (i < j) on the way.
  auto& start = skin.near_start;
  start.assign(n + 1, 1);
  start[0] = 0;
  for (auto& pair : pairs) {
    const auto [i, j] = pair;
    pair = {i < j ? i : j, i < j ? j : i};
    ++start[i + 1];
    ++start[j + 1];
  }
  for (std::uint32_t i = 0; i < n; ++i) start[i + 1] += start[i];
  skin.near.resize(start[n]);
  skin.near_fill.assign(start.begin(), start.end() - 1);
  for (auto [i, j] : pairs) {
    skin.near[skin.near_fill[i]++] = j;
    skin.near[skin.near_fill[j]++] = i;
  }
  for (std::uint32_t i = 0; i < n; ++i) skin.near[start[i + 1] - 1] = kEndOfNear;
  // Nothing predicted yet, every pair due: the wakes are only sized, for the solver marks
  // every ball's course with the last solve, no earlier than any wake was seen (writing
  // them all took longer than the pair scan's filter at 10^5). When the solve count
  // nears overflow it starts again, and then every wake is cleared.
  if (skin.skin_tick >= (1u << 30)) {
    skin.pair_wake.assign(pairs.size(), {});
    skin.skin_tick = 1;
  } else {
    skin.pair_wake.resize(pairs.size());
  }
  skin.skin_dt = dt;
  skin.skin_valid = true;
  ++skin.skin_builds;
}

}  // namespace fts::sim::detail
