// fts-gas-bench: body-steps per second of each physics model on a hard-disc gas (radius
// 1, mass 1, speed 10, packing 0.2, walls: the shipped gas-N scenes), and of Box2D 2.4.1
// on the same initial balls when it was found at build time, all in one run so that
// ratios are measured on one machine at one time. Reports figures; never fails on time.
//
// usage: fts-gas-bench [--n 10000] [--ticks 300] [--hz 100] [--engines LIST]
//                      [--seed S]
//   LIST: comma-separated of seed, discrete, continuous, box2d (default: all available)
//   S: the generator's seed (gas-1000.json uses 1, gas-10000 2, gas-100000 3; default 2)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "fts/sim/physics.hpp"
#include "fts/sim/scene.hpp"

#ifdef FTS_HAVE_BOX2D
#include <box2d/box2d.h>
#endif

namespace {

using namespace fts::sim;
using Clock = std::chrono::steady_clock;

struct Result {
  std::string engine;
  double seconds = 0;
  std::uint64_t body_steps = 0;
  std::uint64_t collisions = 0;
  double drift = 0;        // max over ticks |E - E0| / E0
  double penetration = 0;  // largest overlap after the last tick (u)
};

void print(const Result& r, std::size_t n) {
  const double ns = r.seconds * 1e9 / static_cast<double>(r.body_steps);
  std::printf("| %-12s | %7zu | %8.1f | %7.2f | %9llu | %8.1e | %8.2g |\n", r.engine.c_str(), n, ns,
              1e3 / ns, static_cast<unsigned long long>(r.collisions), r.drift, r.penetration);
  std::fflush(stdout);
}

// The shipped scenes' gas: side for packing 0.2, rounded to 0.01 u as in gas-N.json.
World make_gas(std::int64_t n, std::uint64_t seed) {
  Scene scene;
  const double side = std::round(std::sqrt(static_cast<double>(n) * 3.14159265358979 / 0.2) * 100.0) / 100.0;
  scene.arena = {side, side, Boundary::walls};
  Generator g;
  g.count = n;
  g.radius = 1.0;
  g.mass = 1.0;
  g.speed_u_per_s = 10.0;
  g.seed = seed;
  scene.generators.push_back(g);
  World w;
  if (auto err = build_world(scene, w)) {
    std::fprintf(stderr, "fts-gas-bench: %s\n", err->c_str());
    std::exit(1);
  }
  return w;
}

Result run_fts(const World& start, Model model, double hz, int ticks) {
  World w = start;
  PhysicsSettings s;
  s.model = model;
  const StepConstants k = make_step_constants(s, 1.0 / hz);
  StepReport rep;
  Result r;
  r.engine = std::string(to_string(model));
  const double e0 = kinetic_energy(w.balls);
  for (int t = 0; t < ticks; ++t) {
    r.body_steps += w.balls.size();
    const auto t0 = Clock::now();
    step(w, s, k, rep);
    r.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    r.collisions += rep.collisions;
    r.drift = std::max(r.drift, std::fabs(kinetic_energy(w.balls) - e0) / e0);
  }
  r.penetration = max_penetration(w.balls);
  return r;
}

#ifdef FTS_HAVE_BOX2D
// Counts contacts that begin (Box2D's nearest notion of a collision).
class Counter : public b2ContactListener {
 public:
  void BeginContact(b2Contact* c) override {
    if (c->GetFixtureA()->GetBody()->GetType() == b2_dynamicBody &&
        c->GetFixtureB()->GetBody()->GetType() == b2_dynamicBody)
      ++begun;
  }
  std::uint64_t begun = 0;
};

Result run_box2d(const World& start, double hz, int ticks) {
  b2World world(b2Vec2(0.0f, 0.0f));
  world.SetAllowSleeping(false);
  Counter counter;
  world.SetContactListener(&counter);
  const float w = static_cast<float>(start.arena.width_u), h = static_cast<float>(start.arena.height_u);
  b2BodyDef wall_def;
  b2Body* walls = world.CreateBody(&wall_def);
  const b2Vec2 corners[4] = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  for (int i = 0; i < 4; ++i) {
    b2EdgeShape edge;
    edge.SetTwoSided(corners[i], corners[(i + 1) % 4]);
    b2FixtureDef fd;
    fd.shape = &edge;
    fd.friction = 0.0f;
    fd.restitution = 1.0f;
    walls->CreateFixture(&fd);
  }
  std::vector<b2Body*> bodies;
  bodies.reserve(start.balls.size());
  for (const Ball& b : start.balls) {
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position.Set(static_cast<float>(b.pos.x), static_cast<float>(b.pos.y));
    def.linearVelocity.Set(static_cast<float>(b.vel.x), static_cast<float>(b.vel.y));
    def.fixedRotation = true;
    b2Body* body = world.CreateBody(&def);
    b2CircleShape circle;
    circle.m_radius = static_cast<float>(b.radius);
    b2FixtureDef fd;
    fd.shape = &circle;
    fd.density = static_cast<float>(b.mass / (3.14159265358979 * b.radius * b.radius));
    fd.friction = 0.0f;
    fd.restitution = 1.0f;
    body->CreateFixture(&fd);
    bodies.push_back(body);
  }
  auto energy = [&] {
    double e = 0;
    for (b2Body* b : bodies) {
      const b2Vec2 v = b->GetLinearVelocity();
      e += 0.5 * b->GetMass() * (static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y);
    }
    return e;
  };
  Result r;
  r.engine = "box2d-2.4.1";
  const double e0 = energy();
  const float dt = static_cast<float>(1.0 / hz);
  for (int t = 0; t < ticks; ++t) {
    r.body_steps += bodies.size();
    const auto t0 = Clock::now();
    world.Step(dt, 8, 3);
    r.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    r.drift = std::max(r.drift, std::fabs(energy() - e0) / e0);
  }
  r.collisions = counter.begun;
  std::vector<Ball> end = start.balls;
  for (std::size_t i = 0; i < end.size(); ++i) {
    const b2Vec2 p = bodies[i]->GetPosition();
    end[i].pos = {p.x, p.y};
  }
  r.penetration = max_penetration(end);
  return r;
}
#endif

bool wants(const std::string& list, const std::string& name) {
  return ("," + list + ",").find("," + name + ",") != std::string::npos;
}

}  // namespace

int main(int argc, char** argv) {
  std::int64_t n = 10000;
  int ticks = 300;
  double hz = 100.0;
  std::uint64_t seed = 2;
  std::string engines = "seed,discrete,continuous,box2d";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "usage: fts-gas-bench [--n N] [--ticks T] [--hz HZ] [--engines LIST] [--seed S]\n");
      return 2;
    }
    const std::string v = argv[++i];
    if (a == "--n") n = std::atoll(v.c_str());
    else if (a == "--ticks") ticks = std::atoi(v.c_str());
    else if (a == "--hz") hz = std::atof(v.c_str());
    else if (a == "--engines") engines = v;
    else if (a == "--seed") seed = std::strtoull(v.c_str(), nullptr, 10);
    else {
      std::fprintf(stderr, "fts-gas-bench: unknown flag %s\n", a.c_str());
      return 2;
    }
  }
  if (n < 1 || ticks < 1 || !(hz > 0)) {
    std::fprintf(stderr, "fts-gas-bench: --n, --ticks and --hz must be positive\n");
    return 2;
  }
  const World gas = make_gas(n, seed);
  std::printf("gas-%lld: radius 1, speed 10, packing 0.2, walls, %g Hz, %d ticks, one thread\n\n",
              static_cast<long long>(n), hz, ticks);
  std::printf("| engine       |  bodies | ns/body-step | M body-steps/s | collisions | energy drift | end overlap (u) |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (Model m : {Model::seed, Model::discrete, Model::continuous})
    if (wants(engines, std::string(to_string(m)))) print(run_fts(gas, m, hz, ticks), gas.balls.size());
#ifdef FTS_HAVE_BOX2D
  if (wants(engines, "box2d")) print(run_box2d(gas, hz, ticks), gas.balls.size());
#else
  if (wants(engines, "box2d")) std::printf("(box2d: not built; install libbox2d-dev and re-run cmake)\n");
#endif
  return 0;
}
