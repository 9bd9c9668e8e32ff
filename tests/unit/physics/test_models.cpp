// The three models on small worlds: conservation, boundaries, tunnelling.
#include <catch2/catch.hpp>

#include <cmath>

#include "../../support/physics_fixtures.hpp"
#include "fts/sim/detmath.hpp"

using namespace fts::sim;
using namespace fts::test;

TEST_CASE("Models: head-on equal masses swap velocities in every model", "[models]") {
  for (Model m : kAllModels) {
    INFO(to_string(m));
    World w = walled(400, 200, {ball(1, 100, 100, 50, 0, 10, 1), ball(2, 300, 100, -50, 0, 10, 1)});
    const auto hits = run(w, settings(m), 0.01, 250);  // they meet after 1.8 s
    CHECK(hits == 1);
    CHECK(w.balls[0].vel.x == Approx(-50));
    CHECK(w.balls[1].vel.x == Approx(50));
    CHECK(momentum(w.balls).x == Approx(0).margin(1e-9));
  }
}

TEST_CASE("Models: walls reflect and are never crossed", "[models]") {
  for (Model m : kAllModels) {
    INFO(to_string(m));
    World w = walled(100, 100, {ball(1, 50, 50, 937, -411, 5, 2)});
    StepReport rep;
    const auto s = settings(m);
    const auto k = make_step_constants(s, 0.01);
    std::uint64_t hits = 0;
    for (int i = 0; i < 1000; ++i) {
      step(w, s, k, rep);
      hits += rep.wall_hits;
      REQUIRE(count_escaped(w) == 0);
    }
    CHECK(hits > 100);
    CHECK(kinetic_energy(w.balls) == Approx(0.5 * 2 * (937.0 * 937 + 411.0 * 411)));
  }
}

TEST_CASE("Models: open edges remove a ball whose centre leaves", "[models]") {
  for (Model m : kAllModels) {
    INFO(to_string(m));
    World w;
    w.arena = {500, 300, Boundary::open};
    w.balls = {ball(1, 490, 150, 100, 0, 10, 1), ball(2, 250, 150, 0, 0, 10, 1)};
    StepReport rep;
    const auto s = settings(m);
    step(w, s, make_step_constants(s, 0.01), rep);  // 491: on the platform
    CHECK(rep.fallen.empty());
    for (int i = 0; i < 10 && rep.fallen.empty(); ++i) step(w, s, make_step_constants(s, 0.01), rep);
    REQUIRE(rep.fallen.size() == 1);
    CHECK(rep.fallen[0] == 1);
    REQUIRE(w.balls.size() == 1);
    CHECK(w.balls[0].id == 2);
  }
}

TEST_CASE("Models: a ball already off an open edge falls, even standing still", "[models]") {
  for (Model m : kAllModels) {
    INFO(to_string(m));
    World w;
    w.arena = {500, 300, Boundary::open};
    w.balls = {ball(1, -0.5, 150, 0, 0, 10, 1), ball(2, 250, 150, 0, 0, 10, 1)};
    StepReport rep;
    const auto s = settings(m);
    step(w, s, make_step_constants(s, 0.01), rep);
    REQUIRE(rep.fallen.size() == 1);
    CHECK(rep.fallen[0] == 1);
  }
}

TEST_CASE("Models: a fast rocket tunnels in discrete but not in continuous", "[models]") {
  // 100 000 u/s at 10 Hz is 10 000 u per tick: far more than the target's width.
  auto scene = [] {
    return walled(30000, 300, {ball(1, 20, 150, 100000, 0, 3, 5), ball(2, 5000, 150, 0, 0, 16, 40)});
  };
  World cont = scene(), disc = scene();
  CHECK(run(cont, settings(Model::continuous), 0.1, 1) == 1);
  CHECK(run(disc, settings(Model::discrete), 0.1, 1) == 0);
  CHECK(disc.balls[1].vel.x == 0.0);   // never touched
  CHECK(cont.balls[1].vel.x > 0.0);    // struck
}

TEST_CASE("Models: continuous leaves no overlap behind", "[models]") {
  World w = walled(100, 100, {});
  for (std::uint32_t i = 0; i < 40; ++i) {
    w.balls.push_back(ball(i + 1, 10 + (i % 8) * 11.0, 10 + (i / 8) * 11.0, 37.0 * ((i * 7) % 5) - 70,
                           29.0 * ((i * 3) % 7) - 80, 4, 1 + i % 3));
  }
  double pen = 0.0;
  run(w, settings(Model::continuous), 0.01, 2000, &pen);
  CHECK(pen <= 1e-9);
  CHECK(count_escaped(w) == 0);
}

TEST_CASE("Models: discrete sub-steps shrink the overlap", "[models]") {
  auto scene = [] { return walled(200, 100, {ball(1, 50, 50, 300, 0, 5, 1), ball(2, 80, 50, -300, 0, 5, 1)}); };
  double pen1 = 0, pen8 = 0;
  World a = scene(), b = scene();
  // Measure the penetration the discrete model sees before resolving: step to contact.
  run(a, settings(Model::discrete, 1), 0.01, 20, &pen1);
  run(b, settings(Model::discrete, 8), 0.01, 20, &pen8);
  // After resolution both are clean; energy is conserved exactly by the impulse.
  CHECK(pen1 <= 1e-9);
  CHECK(pen8 <= 1e-9);
  CHECK(kinetic_energy(a.balls) == Approx(kinetic_energy(b.balls)));
}

TEST_CASE("Friction: velocity decays by 0.991 per 0.01 s at every tick rate", "[models]") {
  for (double hz : {50.0, 100.0, 200.0}) {
    INFO(hz << " Hz");
    World w;
    w.arena = {1e6, 1e6, Boundary::open};
    w.balls = {ball(1, 5e5, 5e5, 100, 0, 1, 1)};
    auto s = settings(Model::continuous);
    s.friction = true;
    const auto n = static_cast<long>(hz);  // one second
    run(w, s, 1.0 / hz, n);
    CHECK(w.balls[0].vel.x == Approx(100 * std::pow(0.991, 100)).epsilon(1e-12));
  }
  SECTION("the unit is the configured frame: a longer frame decays less per second") {
    for (double frame_s : {0.01, 0.02, 0.005}) {
      INFO("frame " << frame_s << " s");
      World w;
      w.arena = {1e6, 1e6, Boundary::open};
      w.balls = {ball(1, 5e5, 5e5, 100, 0, 1, 1)};
      auto s = settings(Model::discrete);
      s.friction = true;
      s.frame_s = frame_s;
      run(w, s, 0.01, 100);  // one second at 100 Hz
      CHECK(w.balls[0].vel.x == Approx(100 * std::pow(0.991, 1.0 / frame_s)).epsilon(1e-12));
    }
  }
  SECTION("a thrust axis is spared the cut-off for that tick only") {
    World w;
    w.arena = {100, 100, Boundary::open};
    w.balls = {ball(1, 50, 50, 0.5, 0.5, 1, 1)};
    w.balls[0].thrust_axes = kThrustX;
    auto s = settings(Model::continuous);
    s.friction = true;
    run(w, s, 0.01, 1);
    CHECK(w.balls[0].vel.x == 0.5 * 0.991);
    CHECK(w.balls[0].vel.y == 0.0);
    CHECK(w.balls[0].thrust_axes == 0);  // cleared by the step
    run(w, s, 0.01, 1);
    CHECK(w.balls[0].vel.x == 0.0);
  }
  SECTION("a component below 1 u/s stops") {
    World w;
    w.arena = {100, 100, Boundary::open};
    w.balls = {ball(1, 50, 50, 1.005, 30, 1, 1)};
    auto s = settings(Model::discrete);
    s.friction = true;
    run(w, s, 0.01, 1);
    CHECK(w.balls[0].vel.x == 0.0);
    CHECK(w.balls[0].vel.y > 0.0);
  }
}

TEST_CASE("Deterministic math: det_pow/det_exp/det_log agree with libm", "[models]") {
  for (double e : {0.5, 2.0, 0.25, 1.0 / 3.0, 100.0 / 60.0, 7.25}) {
    CHECK(det_pow(0.991, e) == Approx(std::pow(0.991, e)).epsilon(1e-14));
  }
  for (double x : {1e-300, 0.001, 0.5, 1.0, 2.0, 1e10, 1e300}) CHECK(det_log(x) == Approx(std::log(x)).epsilon(1e-14));
  for (double x : {-700.0, -5.0, 0.0, 1e-3, 3.0, 700.0}) CHECK(det_exp(x) == Approx(std::exp(x)).epsilon(1e-14));
}

TEST_CASE("Step buffers: the world owns them - a copy starts empty and steps the same", "[models]") {
  for (Model m : kAllModels) {
    INFO(to_string(m));
    World a;
    a.arena = {60, 60, Boundary::walls};
    for (std::uint32_t id = 1; id <= 100; ++id)
      a.balls.push_back(ball(id, 3.0 + 5.5 * ((id - 1) % 10), 3.0 + 5.5 * ((id - 1) / 10), 7.0 * (id % 3) - 7.0,
                             5.0 * (id % 5) - 10.0, 1, 1 + id % 4));
    auto s = settings(m);
    s.broadphase = Broadphase::grid;
    run(a, s, 0.01, 5);
    if (m == Model::continuous) REQUIRE(a.buffers.bodies.size() == a.balls.size());
    World b = a;
    // Capacity is not state: nothing is copied.
    CHECK(b.buffers.bodies.capacity() == 0);
    CHECK(b.buffers.pairs.capacity() == 0);
    CHECK(b.buffers.grid.boxes().capacity() == 0);
    // Stepping one world between the other's steps changes nothing (no shared scratch).
    World c = a;
    for (int i = 0; i < 20; ++i) {
      run(a, s, 0.01, 1);
      run(c, s, 0.01, 1);
    }
    run(b, s, 0.01, 20);
    CHECK(state_hash(a.balls) == state_hash(b.balls));
    CHECK(state_hash(c.balls) == state_hash(b.balls));
  }
}

namespace {

// A walled square arena with an nx x ny lattice of unit balls (radius 1, mass 1), `gap`
// apart from (x0, y0), all at velocity (vx, vy); ids from 1.
World lattice(double side, int nx, int ny, double x0, double y0, double gap, double vx, double vy) {
  World w;
  w.arena = {side, side, Boundary::walls};
  std::uint32_t id = 1;
  for (int gy = 0; gy < ny; ++gy)
    for (int gx = 0; gx < nx; ++gx, ++id) w.balls.push_back(ball(id, x0 + gap * gx, y0 + gap * gy, vx, vy, 1, 1));
  return w;
}

PhysicsSettings continuous_grid() {
  auto s = settings(Model::continuous);
  s.broadphase = Broadphase::grid;
  return s;
}

}  // namespace

TEST_CASE("Continuous skin: a ball turned round between ticks is predicted again", "[models]") {
  // A lattice drifting as one body: no pair approaches, so every listed pair is put off
  // for many ticks. Then one ball is turned round toward its neighbour 0.5 u away; it
  // stays inside its skin, so only the kept prediction's check can see the new line.
  World cached = lattice(200, 10, 10, 20, 20, 2.5, 10, 0);
  const auto s = continuous_grid();
  const auto k = make_step_constants(s, 0.01);
  World fresh = cached;
  StepReport rc, rf;
  std::uint64_t collisions = 0;
  for (int tick = 0; tick < 20; ++tick) {
    if (tick == 5)
      for (World* w : {&cached, &fresh}) w->balls[55].vel = {-10, 0};
    step(cached, s, k, rc);
    fresh.buffers = StepBuffers{};
    step(fresh, s, k, rf);
    REQUIRE(rc.collisions == rf.collisions);
    REQUIRE(state_hash(cached.balls) == state_hash(fresh.balls));
    collisions += rc.collisions;
  }
  CHECK(collisions > 0);
  // Built at tick 0 and again once the lattice has drifted a skin's width (tick 10):
  // the turn at tick 5 met predictions kept from the first build.
  CHECK(cached.buffers.skin_builds == 2);
}

TEST_CASE("Continuous skin: a cached skin gives the same bits as one rebuilt every tick", "[models]") {
  // A gas with a wide spread of speeds (some balls leave their skin every tick, the
  // skin is rebuilt every few ticks), a rocket that crosses many skins, an open edge
  // that removes balls (indices shift), a ball resized between ticks, masses changed.
  for (Boundary edge : {Boundary::walls, Boundary::open}) {
    INFO((edge == Boundary::walls ? "walls" : "open"));
    World cached;
    cached.arena = {120, 120, edge};
    std::uint32_t id = 1;
    for (int gy = 0; gy < 14; ++gy)
      for (int gx = 0; gx < 14; ++gx, ++id) {
        const double speed = 2.0 + 9.0 * (id % 7);
        cached.balls.push_back(ball(id, 4.0 + 8.2 * gx, 4.0 + 8.2 * gy, speed * ((id % 3) - 1.0),
                                    speed * ((id % 5) - 2.0) * 0.5, 1.0 + 0.25 * (id % 3), 1 + id % 4));
      }
    cached.balls.push_back(ball(id, 60, 2, 3000, 1700, 0.5, 1));
    auto s = settings(Model::continuous);
    s.broadphase = Broadphase::grid;
    const auto k = make_step_constants(s, 0.01);
    const auto k_half = make_step_constants(s, 0.005);
    World fresh = cached;
    StepReport rc, rf;
    std::uint64_t collisions = 0;
    for (int tick = 0; tick < 200; ++tick) {
      if (tick == 80 && cached.balls.size() > 3) {
        cached.balls[3].radius *= 1.5;
        fresh.balls[3].radius *= 1.5;
      }
      // Lines changed between ticks (the kept predictions must notice): a ball turned
      // round, and a ball put just beside another, heading into it.
      if (tick == 100 || tick == 130) {
        for (World* w : {&cached, &fresh}) {
          const std::size_t n = w->balls.size();
          w->balls[n / 3].vel = w->balls[n / 3].vel * -1.0;
          Ball& a = w->balls[n / 2];
          const Ball& b = w->balls[n / 2 + 1];
          a.pos = b.pos + Vec2{a.radius + b.radius + 0.01, 0.0};
          a.vel = b.vel + Vec2{-20.0, 0.0};
        }
      }
      // Masses changed between ticks, nothing else (the solver's copies must notice).
      if (tick == 115)
        for (World* w : {&cached, &fresh})
          for (std::size_t i = 0; i < w->balls.size(); i += 2) w->balls[i].mass *= 2.0;
      // And a different tick length for a while (the wakes count ticks).
      const auto& kt = tick >= 150 && tick < 160 ? k_half : k;
      step(cached, s, kt, rc);
      fresh.buffers = StepBuffers{};  // no cache: the skin is built from scratch
      step(fresh, s, kt, rf);
      REQUIRE(rc.collisions == rf.collisions);
      REQUIRE(state_hash(cached.balls) == state_hash(fresh.balls));
      collisions += rc.collisions;
    }
    CHECK(collisions > 100);
    // The cache was really used: far fewer builds than ticks.
    CHECK(cached.buffers.skin_builds < 150);
    CHECK(cached.buffers.skin_builds > 1);
    // And the grid agrees with all pairs.
    World pairs = fresh;
    World grid = fresh;
    auto sp = s;
    sp.broadphase = Broadphase::pairs;
    run(pairs, sp, 0.01, 50);
    run(grid, s, 0.01, 50);
    CHECK(state_hash(pairs.balls) == state_hash(grid.balls));
  }
}

TEST_CASE("Continuous skin: every ball faster than a new skin leaves it, however many", "[models]") {
  // 70 balls at 1000 u/s among 7921 at rest: half a skin is about 9.4 u, less than their
  // 10 u per tick, so each leaves its new skin at once, more balls than the escaped list
  // takes before a rebuild (32 + n / 256 = 63). All of them must be escaped and tested
  // against the top wall, which each reaches within the first tick (turned back, inside).
  World w = lattice(300, 89, 89, 3, 3, 3, 0, 0);
  std::uint32_t id = static_cast<std::uint32_t>(w.balls.size()) + 1;
  for (int k = 0; k < 70; ++k, ++id) w.balls.push_back(ball(id, 5.0 + 4.0 * k, 290, 0, 1000, 1, 1));
  const auto s = continuous_grid();
  StepReport rep;
  step(w, s, make_step_constants(s, 0.01), rep);
  CHECK(rep.wall_hits == 70);
  std::size_t inside = 0;
  for (const Ball& b : w.balls) inside += b.pos.y <= 299.0 && b.vel.y <= 0.0;
  CHECK(inside == w.balls.size());
  CHECK(kinetic_energy(w.balls) == Approx(70 * 0.5 * 1000.0 * 1000.0));
}
