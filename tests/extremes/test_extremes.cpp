// Numerical extremes, in every model: no NaN or infinity ever leaves the engine.
#include <catch2/catch.hpp>

#include <cmath>

#include "../support/physics_fixtures.hpp"

using namespace fts::sim;
using namespace fts::test;

TEST_CASE("Extremes: mass ratios from 1e-9 to 1e9", "[extremes]") {
  for (Model m : kAllModels) {
    for (double ratio : {1e-9, 1e-6, 1.0, 1e6, 1e9}) {
      INFO(to_string(m) << " ratio " << ratio);
      World w = walled(400, 200, {ball(1, 100, 100, 40, 3, 10, ratio), ball(2, 200, 104, -30, 0, 10, 1)});
      const double e0 = kinetic_energy(w.balls);
      run(w, settings(m), 0.01, 500);
      REQUIRE(all_finite(w.balls));
      CHECK(count_escaped(w) == 0);
      if (m != Model::seed) CHECK(kinetic_energy(w.balls) == Approx(e0).epsilon(1e-9));
    }
  }
}

TEST_CASE("Extremes: coincident centres separate without NaN, the same way every time", "[extremes]") {
  for (Model m : kAllModels) {
    INFO(to_string(m));
    auto make = [] { return walled(100, 100, {ball(1, 50, 50, 0, 0, 5, 1), ball(2, 50, 50, 0, 0, 5, 1)}); };
    World a = make(), b = make();
    run(a, settings(m), 0.01, 3);
    run(b, settings(m), 0.01, 3);
    REQUIRE(all_finite(a.balls));
    CHECK(state_hash(a.balls) == state_hash(b.balls));
    CHECK(max_penetration(a.balls) <= 1e-9);
    CHECK(a.balls[0].pos.y == a.balls[1].pos.y);  // separated along x: the fixed direction
  }
}

TEST_CASE("Extremes: one ball inside another", "[extremes]") {
  for (Model m : kAllModels) {
    INFO(to_string(m));
    World w = walled(200, 200, {ball(1, 100, 100, 0, 0, 40, 10), ball(2, 103, 101, 5, 0, 2, 1)});
    run(w, settings(m), 0.01, 5);
    REQUIRE(all_finite(w.balls));
    CHECK(max_penetration(w.balls) <= 1e-9);
    CHECK(count_escaped(w) == 0);
  }
}

TEST_CASE("Extremes: 1e6 u/s does not tunnel in continuous, even at 10 Hz", "[extremes]") {
  World w = walled(1e6, 100, {ball(1, 10, 50, 1e6, 0, 1, 1), ball(2, 5e4, 50, 0, 0, 1, 1)});
  CHECK(run(w, settings(Model::continuous), 0.1, 1) == 1);
  REQUIRE(all_finite(w.balls));
  CHECK(count_escaped(w) == 0);
  for (Model m : kAllModels) {  // and no model lets it out of the box
    World v = walled(100, 100, {ball(1, 50, 50, 1e6, -3e5, 1, 1)});
    run(v, settings(m), 0.1, 20);
    REQUIRE(all_finite(v.balls));
    CHECK(count_escaped(v) == 0);
  }
}

TEST_CASE("Extremes: coordinates near 1e9", "[extremes]") {
  for (Model m : kAllModels) {
    INFO(to_string(m));
    World w = walled(2e9, 2e9, {ball(1, 1e9, 1e9, 50, 0, 10, 1), ball(2, 1e9 + 100, 1e9, -50, 0, 10, 1)});
    CHECK(run(w, settings(m), 0.01, 200) == 1);
    REQUIRE(all_finite(w.balls));
    CHECK(w.balls[0].vel.x == Approx(-50).epsilon(1e-6));
  }
}

TEST_CASE("Extremes: radius 1e-6", "[extremes]") {
  for (Model m : {Model::discrete, Model::continuous}) {
    INFO(to_string(m));
    World w = walled(1, 1, {ball(1, 0.25, 0.5, 1e-3, 0, 1e-6, 1), ball(2, 0.75, 0.5, -1e-3, 0, 1e-6, 1)});
    const auto hits = run(w, settings(m), 0.01, 30000);
    REQUIRE(all_finite(w.balls));
    CHECK(count_escaped(w) == 0);
    if (m == Model::continuous) CHECK(hits >= 1);  // the discrete model may step over them
  }
  World s = walled(1, 1, {ball(1, 0.5, 0.5, 0, 0, 1e-6, 1), ball(2, 0.5, 0.5, 0, 0, 1e-6, 1)});
  run(s, settings(Model::seed), 0.01, 3);  // the seed's unit push crosses the whole box
  REQUIRE(all_finite(s.balls));
  CHECK(count_escaped(s) == 0);
}

TEST_CASE("Extremes: 10^6 ticks of a small scene: no NaN, no energy growth", "[extremes]") {
  for (Model m : kAllModels) {
    INFO(to_string(m));
    World w = walled(100, 60, {ball(1, 20, 30, 70, 13, 5, 1), ball(2, 50, 30, -40, 22, 7, 3),
                               ball(3, 80, 20, 10, -50, 4, 0.5), ball(4, 60, 50, -25, -5, 3, 2)});
    const double e0 = kinetic_energy(w.balls);
    run(w, settings(m), 0.01, 1000000);
    REQUIRE(all_finite(w.balls));
    CHECK(count_escaped(w) == 0);
    CHECK(kinetic_energy(w.balls) <= e0 * (1 + 1e-9));
  }
}

TEST_CASE("Extremes: the pile finishes every tick within its event budget", "[extremes]") {
  World w = walled(200, 200, {});
  for (std::uint32_t i = 0; i < 200; ++i) {
    // All 200 within a 10 x 10 square: hopelessly overlapping.
    w.balls.push_back(ball(i + 1, 95 + (i * 37 % 100) / 10.0, 95 + (i * 61 % 100) / 10.0, (i % 7) - 3.0,
                           (i % 5) - 2.0, 2, 1));
  }
  const auto s = settings(Model::continuous);
  const auto k = make_step_constants(s, 0.01);
  StepReport rep;
  for (int t = 0; t < 300; ++t) {
    step(w, s, k, rep);
    REQUIRE(rep.collisions <= 64 * 200 + 4096);
    REQUIRE(all_finite(w.balls));
    REQUIRE(count_escaped(w) == 0);
  }
  CHECK(max_penetration(w.balls) <= 1e-6);
}
