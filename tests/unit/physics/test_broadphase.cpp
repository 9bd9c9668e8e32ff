// The broad phases find exactly the pairs that the all-pairs tests find.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "../../support/physics_fixtures.hpp"
#include "fts/sim/broadphase.hpp"
#include "fts/sim/broadphase_discs.hpp"
#include "fts/sim/rng.hpp"

using namespace fts::sim;
using namespace fts::test;

namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

Pairs brute_force(const std::vector<Ball>& balls) {
  Pairs out;
  for (std::uint32_t i = 0; i < balls.size(); ++i)
    for (std::uint32_t j = i + 1; j < balls.size(); ++j) {
      const double reach = balls[i].radius + balls[j].radius;
      if (length_sq(balls[j].pos - balls[i].pos) <= reach * reach) out.emplace_back(i, j);
    }
  return out;
}

Pairs disc_grid(DiscGrid& grid, const std::vector<Ball>& balls) {
  Pairs out;
  grid.touching_pairs(balls, out);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("DiscGrid: the same touching pairs as all pairs", "[broadphase]") {
  DiscGrid grid;  // reused across cases, as a world reuses it across steps
  Rng rng(7);
  for (int round = 0; round < 40; ++round) {
    INFO("round " << round);
    const int n = 1 + static_cast<int>(rng.uniform(0.0, 600.0));
    const double side = rng.uniform(5.0, 200.0);
    std::vector<Ball> balls;
    for (int i = 0; i < n; ++i) {
      // Mostly similar radii, some tiny, a few giants (round % 4 == 0) and exact duplicates.
      double r = rng.uniform(0.5, 2.0);
      if (i % 17 == 0) r = 1e-3;
      if (round % 4 == 0 && i % 50 == 0) r = rng.uniform(10.0, 40.0);
      Vec2 p{rng.uniform(0.0, side), rng.uniform(0.0, side)};
      if (i > 0 && i % 23 == 0) p = balls.back().pos;
      balls.push_back(ball(static_cast<BallId>(i + 1), p.x, p.y, 0, 0, r, 1));
    }
    CHECK(disc_grid(grid, balls) == brute_force(balls));
  }
  SECTION("exactly touching discs on a cell boundary are found") {
    std::vector<Ball> balls;
    for (int i = 0; i < 50; ++i) balls.push_back(ball(static_cast<BallId>(i + 1), 2.0 * i, 0.0, 0, 0, 1, 1));
    const Pairs found = disc_grid(grid, balls);
    CHECK(found.size() == 49);
    CHECK(found == brute_force(balls));
  }
  SECTION("a dense cluster (ranges longer than the scan's windows), with and without bounds given") {
    std::vector<Ball> balls;
    DiscBounds bounds;
    for (int i = 0; i < 300; ++i) {
      balls.push_back(ball(static_cast<BallId>(i + 1), rng.uniform(0.0, 12.0), rng.uniform(0.0, 12.0), 0, 0, 1, 1));
      bounds.add(balls.back());
    }
    Pairs with_bounds;
    grid.touching_pairs(balls, with_bounds, &bounds);
    std::sort(with_bounds.begin(), with_bounds.end());
    CHECK(with_bounds == brute_force(balls));
    CHECK(disc_grid(grid, balls) == with_bounds);
  }
  SECTION("discs as far out as the scan's padding, and not finite ones, meet only what all pairs meets") {
    std::vector<Ball> balls = {ball(1, 1e300, 1e300, 0, 0, 1, 1), ball(2, 1e300, 1e300, 0, 0, 1, 1),
                               ball(3, 0, 0, 0, 0, 1, 1), ball(4, 1.5, 0, 0, 0, 1, 1),
                               ball(5, std::numeric_limits<double>::quiet_NaN(), 0, 0, 0, 1, 1),
                               ball(6, std::numeric_limits<double>::infinity(), 0, 0, 0, 1, 1)};
    CHECK(disc_grid(grid, balls) == brute_force(balls));
    CHECK(disc_grid(grid, balls) == Pairs{{0, 1}, {2, 3}});
  }
  SECTION("far-flung discs (sparse cells) and a single disc") {
    std::vector<Ball> balls = {ball(1, -1e6, 0, 0, 0, 1, 1), ball(2, 1e6, 5, 0, 0, 1, 1), ball(3, 1e6, 6, 0, 0, 1, 1)};
    CHECK(disc_grid(grid, balls) == Pairs{{1, 2}});
    balls.resize(1);
    CHECK(disc_grid(grid, balls).empty());
  }
}

TEST_CASE("Grid: the same overlapping boxes as all pairs - a query offers every overlapping box", "[broadphase]") {
  Grid grid;
  Rng rng(11);
  for (int round = 0; round < 30; ++round) {
    INFO("round " << round);
    const int n = 1 + static_cast<int>(rng.uniform(0.0, 400.0));
    const double side = rng.uniform(5.0, 150.0);
    auto& boxes = grid.boxes();
    boxes.clear();
    for (int i = 0; i < n; ++i) {
      double w = rng.uniform(0.5, 3.0), h = rng.uniform(0.5, 3.0);
      if (round % 3 == 0 && i % 40 == 0) w = h = rng.uniform(20.0, 60.0);  // overflow
      const double x = rng.uniform(0.0, side), y = rng.uniform(0.0, side);
      boxes.push_back({x, y, x + w, y + h});
    }
    grid.build();
    Pairs expected, found;
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
      for (std::uint32_t j = i + 1; j < boxes.size(); ++j)
        if (overlaps(boxes[i], boxes[j])) expected.emplace_back(i, j);
    grid.for_each_overlapping_pair([&](std::uint32_t i, std::uint32_t j) { found.emplace_back(i, j); });
    std::sort(found.begin(), found.end());
    CHECK(found == expected);
    // A query box somewhere: every box overlapping it is offered (maybe more).
    const double qx = rng.uniform(0.0, side), qy = rng.uniform(0.0, side);
    const Box q{qx, qy, qx + rng.uniform(0.0, 10.0), qy + rng.uniform(0.0, 10.0)};
    std::vector<std::uint8_t> offered(boxes.size(), 0);
    grid.query(q, [&](std::uint32_t j) { offered[j] = 1; });
    for (std::uint32_t j = 0; j < boxes.size(); ++j)
      if (overlaps(q, boxes[j])) CHECK(offered[j]);
  }
}

TEST_CASE("Grid: square boxes give the pairs whose inscribed discs overlap, and overflow boxes' overlaps", "[broadphase]") {
  // Centres and half widths on a 1/8 grid, so that every sum and difference is exact
  // and "touching" is decided the same way by both sides.
  Grid grid;
  Rng rng(12);
  for (int round = 0; round < 20; ++round) {
    INFO("round " << round);
    const int n = 2 + static_cast<int>(rng.uniform(0.0, 400.0));
    const double side = std::floor(rng.uniform(10.0, 120.0));
    auto eighth = [&](double lo, double hi) { return std::floor(rng.uniform(lo, hi) * 8.0) / 8.0; };
    auto& boxes = grid.boxes();
    boxes.clear();
    for (int i = 0; i < n; ++i) {
      double m = eighth(0.5, 2.5);
      if (round % 4 == 0 && i % 50 == 0) m = eighth(20.0, 40.0);  // overflow
      const double x = eighth(0.0, side), y = eighth(0.0, side);
      boxes.push_back({x - m, y - m, x + m, y + m});
    }
    grid.build();
    Pairs expected, found;
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
      for (std::uint32_t j = i + 1; j < boxes.size(); ++j) {
        const Box& a = boxes[i];
        const Box& b = boxes[j];
        const double dx = (b.x0 + b.x1 - a.x0 - a.x1) / 2, dy = (b.y0 + b.y1 - a.y0 - a.y1) / 2;
        const double reach = (a.x1 - a.x0 + b.x1 - b.x0) / 2;
        const bool giant = grid.is_overflow(i) || grid.is_overflow(j);
        if (giant ? overlaps(a, b) : dx * dx + dy * dy <= reach * reach) expected.emplace_back(i, j);
      }
    BigVector<std::pair<std::uint32_t, std::uint32_t>> out;
    grid.overlapping_disc_pairs(out);
    for (auto [i, j] : out) found.emplace_back(std::min(i, j), std::max(i, j));
    std::sort(found.begin(), found.end());
    CHECK(found == expected);
    if (round == 1) CHECK(expected.size() > 10);  // the test sees pairs at all
  }
}
