// The seed's collision math (GAME_RULES.md "Collisions") and its vector form.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "../../support/physics_fixtures.hpp"
#include "fts/sim/collide.hpp"
#include "fts/sim/rng.hpp"

using namespace fts::sim;
using fts::test::ball;

namespace {
// The 1-D elastic formula along the normal, applied unconditionally (as the seed does).
void vector_response(Ball& a, Ball& b) {
  const Vec2 n = contact_normal(a, b);
  const double vn = dot(b.vel - a.vel, n);
  a.vel += n * (2.0 * b.mass / (a.mass + b.mass) * vn);
  b.vel -= n * (2.0 * a.mass / (a.mass + b.mass) * vn);
}
}  // namespace

TEST_CASE("Collisions: the seed's trigonometric response equals the vector response", "[collide]") {
  Rng rng(12345);
  double worst = 0.0;
  for (int k = 0; k < 10000; ++k) {
    const double r1 = rng.uniform(0.5, 30), r2 = rng.uniform(0.5, 30);
    const double ang_x = rng.uniform(-1, 1), ang_y = rng.uniform(-1, 1);
    const double len = std::sqrt(ang_x * ang_x + ang_y * ang_y) + 1e-9;
    Ball a = ball(1, 100, 100, rng.uniform(-200, 200), rng.uniform(-200, 200), r1, rng.uniform(0.1, 100));
    Ball b = ball(2, 100 + (r1 + r2) * ang_x / len, 100 + (r1 + r2) * ang_y / len, rng.uniform(-200, 200),
                  rng.uniform(-200, 200), r2, rng.uniform(0.1, 100));
    Ball sa = a, sb = b;
    respond_seed(sa, sb);
    vector_response(a, b);
    const double scale = length(a.vel) + length(b.vel) + length(sa.vel) + length(sb.vel);
    const double err = length(sa.vel - a.vel) + length(sb.vel - b.vel);
    worst = std::max(worst, err / scale);
  }
  INFO("worst relative difference " << worst);
  CHECK(worst <= 1e-12);
}

namespace {
long double kinetic(const Ball& a, const Ball& b) {
  auto e = [](const Ball& x) {
    return 0.5L * x.mass * (static_cast<long double>(x.vel.x) * x.vel.x + static_cast<long double>(x.vel.y) * x.vel.y);
  };
  return e(a) + e(b);
}
}  // namespace

TEST_CASE("Collisions: at contact the elastic response has no energy bias", "[collide]") {
  // Pairs as the continuous model collides them: equal radii, centres r_a + r_b = 2
  // apart or a few ulp more, approaching. The energy error of each response is
  // rounding; summed over many it must not have a sign. A response through the unit
  // normal d / |d| has one (it gained energy at every collision of the gas), which the
  // second sum shows, so this scene does reproduce the trap.
  Rng rng(99);
  long double sum = 0, sum_abs = 0, unit_sum = 0, unit_abs = 0;
  for (int k = 0; k < 100000; ++k) {
    const double angle = rng.uniform(-3.14159, 3.14159);
    const double gap = 1.0 + rng.uniform(0.0, 4.0) * 2.2e-16;
    const double x = rng.uniform(0, 300), y = rng.uniform(0, 300);
    const Ball a0 = ball(1, x, y, rng.uniform(-20, 20), rng.uniform(-20, 20), 1, 1);
    const Ball b0 = ball(2, x + 2.0 * gap * std::cos(angle), y + 2.0 * gap * std::sin(angle), rng.uniform(-20, 20),
                         rng.uniform(-20, 20), 1, 1);
    Ball a = a0, b = b0;
    if (!respond_elastic(a, b, contact_direction(a, b))) continue;
    const long double de = kinetic(a, b) - kinetic(a0, b0);
    sum += de;
    sum_abs += std::fabs(de);
    a = a0, b = b0;
    const Vec2 n = contact_normal(a, b);
    const double vn = dot(b.vel - a.vel, n);
    a.vel += n * vn;
    b.vel -= n * vn;
    const long double de_unit = kinetic(a, b) - kinetic(a0, b0);
    unit_sum += de_unit;
    unit_abs += std::fabs(de_unit);
  }
  INFO("sum " << static_cast<double>(sum) << " of |sum| " << static_cast<double>(sum_abs) << "; through the unit normal "
              << static_cast<double>(unit_sum) << " of " << static_cast<double>(unit_abs));
  REQUIRE(sum_abs > 0);
  CHECK(std::fabs(sum) < 0.05L * sum_abs);
  CHECK(unit_sum > 0.3L * unit_abs);
}

TEST_CASE("Collisions: the seed's limit M1 >> M2 leaves v1 unaffected", "[collide]") {
  for (double ratio : {1e6, 1e9}) {
    Ball a = ball(1, 0, 0, 10, 0, 1, ratio), b = ball(2, 2, 0, 0, 0, 1, 1);
    REQUIRE(respond_elastic(a, b, contact_normal(a, b)));
    CHECK(a.vel.x == Approx(10).epsilon(1e-5));
    CHECK(b.vel.x == Approx(20).epsilon(1e-5));  // the light ball leaves at twice the speed
  }
}

TEST_CASE("Collisions: the seed's limit M1 << M2 (v2 = 0, head-on) makes v1 become -v1", "[collide]") {
  for (double ratio : {1e-6, 1e-9}) {
    Ball a = ball(1, 0, 0, 10, 0, 1, ratio), b = ball(2, 2, 0, 0, 0, 1, 1);
    Ball sa = a, sb = b;
    REQUIRE(respond_elastic(a, b, contact_normal(a, b)));
    CHECK(a.vel.x == Approx(-10).epsilon(1e-5));
    CHECK(std::fabs(b.vel.x) < 1e-4);
    respond_seed(sa, sb);
    CHECK(sa.vel.x == Approx(-10).epsilon(1e-5));
  }
}

TEST_CASE("Collisions: head-on equal masses swap velocities", "[collide]") {
  Ball a = ball(1, 0, 0, 3, 0, 1, 2), b = ball(2, 2, 0, -5, 0, 1, 2);
  REQUIRE(respond_elastic(a, b, contact_normal(a, b)));
  CHECK(a.vel.x == -5.0);
  CHECK(b.vel.x == 3.0);
  CHECK(a.vel.y == 0.0);
}

TEST_CASE("Collisions: a glancing hit keeps the tangential components", "[collide]") {
  // Normal along +x: the y components must come through untouched.
  Ball a = ball(1, 0, 0, 4, 7, 1, 1), b = ball(2, 2, 0, -1, -3, 1, 3);
  REQUIRE(respond_elastic(a, b, contact_normal(a, b)));
  CHECK(a.vel.y == 7.0);
  CHECK(b.vel.y == -3.0);
  Ball sa = ball(1, 0, 0, 4, 7, 1, 1), sb = ball(2, 2, 0, -1, -3, 1, 3);
  respond_seed(sa, sb);
  CHECK(sa.vel.y == Approx(7.0).margin(1e-12));
  CHECK(sb.vel.y == Approx(-3.0).margin(1e-12));
}

TEST_CASE("Collisions: separating pairs get no impulse", "[collide]") {
  Ball a = ball(1, 0, 0, -1, 0, 1, 1), b = ball(2, 2, 0, 1, 0, 1, 1);
  CHECK_FALSE(respond_elastic(a, b, contact_normal(a, b)));
  CHECK(a.vel.x == -1.0);
}

TEST_CASE("Collisions: the seed's push-apart is guarded and bounded", "[collide]") {
  SECTION("coincident centres move ball 1 along +x, deterministically") {
    Ball a = ball(1, 5, 5, 0, 0, 2, 1), b = ball(2, 5, 5, 0, 0, 2, 1);
    const int steps = push_apart_seed(a, b);
    CHECK(steps == 5);  // 1, 2, 3, 4 overlap; 5 > r1 + r2 = 4
    CHECK(a.pos.x == 10.0);
    CHECK(a.pos.y == 5.0);
  }
  SECTION("a zero difference on one axis moves only the other") {
    Ball a = ball(1, 5, 5, 0, 0, 2, 1), b = ball(2, 4, 5, 0, 0, 2, 1);
    push_apart_seed(a, b);
    CHECK(a.pos.y == 5.0);
    CHECK(a.pos.x > 8.0);
  }
  SECTION("a huge overlap stops after the iteration bound and still separates") {
    Ball a = ball(1, 0, 0, 0, 0, 1e6, 1), b = ball(2, 0.5, 0, 0, 0, 1e6, 1);
    const int steps = push_apart_seed(a, b, 100);
    CHECK(steps == 100);
    CHECK(length(a.pos - b.pos) > 2e6);
  }
}

TEST_CASE("Collisions: separation is weighted by inverse mass", "[collide]") {
  Ball a = ball(1, 0, 0, 0, 0, 1, 3), b = ball(2, 1, 0, 0, 0, 1, 1);
  separate(a, b, contact_normal(a, b), 1.0);
  CHECK(a.pos.x == Approx(-0.25));
  CHECK(b.pos.x == Approx(1.75));
}

TEST_CASE("Collisions: a ball of infinite mass is immovable - two of them do not act on each other", "[collide]") {
  const double inf = std::numeric_limits<double>::infinity();
  SECTION("vector response: the other ball reflects, the post keeps its velocity") {
    Ball post = ball(1, 0, 0, 0, 0, 1, inf), b = ball(2, 2, 0, -50, 7, 1, 40);
    CHECK(respond_elastic(post, b, contact_direction(post, b)));
    CHECK(post.vel == Vec2{});
    CHECK(b.vel.x == 50.0);
    CHECK(b.vel.y == 7.0);
    Ball c = ball(3, 0, 0, 30, 0, 1, 40), post2 = ball(4, 2, 0, 0, 0, 1, inf);  // the post second
    CHECK(respond_elastic(c, post2, contact_direction(c, post2)));
    CHECK(c.vel.x == -30.0);
    CHECK(post2.vel == Vec2{});
  }
  SECTION("seed response: the limit M1 >> M2") {
    Ball post = ball(1, 0, 0, 0, 0, 1, inf), b = ball(2, 2, 0, -50, 0, 1, 40);
    respond_seed(post, b);
    CHECK(post.vel.x == 0.0);
    CHECK(b.vel.x == Approx(50.0));
    CHECK(std::isfinite(b.vel.y));
    Ball c = ball(3, 0, 0, 30, 0, 1, 40), post2 = ball(4, 2, 0, 0, 0, 1, inf);
    respond_seed(c, post2);
    CHECK(c.vel.x == Approx(-30.0));
    CHECK(post2.vel.x == 0.0);
  }
  SECTION("separation moves only the movable ball") {
    Ball post = ball(1, 0, 0, 0, 0, 1, inf), b = ball(2, 1, 0, 0, 0, 1, 1);
    separate(post, b, contact_normal(post, b), 1.0);
    CHECK(post.pos == Vec2{});
    CHECK(b.pos.x == 2.0);
  }
  SECTION("two posts: no impulse, no push, nothing becomes NaN") {
    Ball a = ball(1, 0, 0, 10, 0, 1, inf), b = ball(2, 1.5, 0, -10, 0, 1, inf);
    CHECK_FALSE(respond_elastic(a, b, contact_direction(a, b)));
    separate(a, b, contact_normal(a, b), 0.5);
    respond_seed(a, b);
    CHECK(a.pos == Vec2{});
    CHECK(b.pos.x == 1.5);
    CHECK(a.vel.x == 10.0);
    CHECK(b.vel.x == -10.0);
  }
}
