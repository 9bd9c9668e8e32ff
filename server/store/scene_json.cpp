#include "store/scene_json.hpp"

#include <cmath>

#include "fts/room/json_fields.hpp"

namespace fts::store {

// The JSON helpers and text conversions of the record format live in fts_room.
using namespace fts::room;
namespace {

template <class T, class Parse>
T parse_enum(const Fields& f, std::string_view key, T fallback, Parse parse, const char* allowed) {
  if (!f.has(key)) return fallback;
  const std::string s = f.string(key);
  if (auto v = parse(s)) return *v;
  f.fail(key, std::string("must be one of ") + allowed + ", got \"" + s + "\"");
}

sim::BallSpec parse_ball(const nlohmann::json& j, const std::string& path) {
  Fields f(j, path);
  f.only({"x", "y", "vx", "vy", "r", "m"});
  sim::BallSpec b;
  b.x = f.number("x");
  b.y = f.number("y");
  b.vx = f.number_or("vx", 0.0);
  b.vy = f.number_or("vy", 0.0);
  b.r = f.number("r");
  b.m = f.number("m");
  require_positive(f, "r", b.r);
  require_positive(f, "m", b.m);
  return b;
}

sim::Generator parse_generator(const nlohmann::json& j, const std::string& path) {
  Fields f(j, path);
  f.only({"count", "radius", "mass", "speed", "seed", "region", "overlap"});
  sim::Generator g;
  g.count = f.integer("count");
  if (g.count < 0 || g.count > 10'000'000) f.fail("count", "must be in 0..10000000, got " + std::to_string(g.count));
  g.radius = f.number("radius");
  g.mass = f.number("mass");
  g.speed_u_per_s = f.number_or("speed", 0.0);
  require_positive(f, "radius", g.radius);
  require_positive(f, "mass", g.mass);
  if (g.speed_u_per_s < 0.0) f.fail("speed", "must be >= 0, got " + nlohmann::json(g.speed_u_per_s).dump());
  const std::int64_t seed = f.integer_or("seed", 1);
  if (seed < 0) f.fail("seed", "must be >= 0, got " + std::to_string(seed));
  g.seed = static_cast<std::uint64_t>(seed);
  g.allow_overlap = f.boolean_or("overlap", false);
  if (f.has("region")) {
    const auto& r = f.at("region");
    if (!r.is_array() || r.size() != 4) f.fail("region", "must be [x0, y0, x1, y1], got " + r.dump());
    double v[4];
    for (int i = 0; i < 4; ++i) {
      if (!r[i].is_number()) f.fail("region", "must hold 4 numbers, got " + r.dump());
      v[i] = r[i].get<double>();
      if (!std::isfinite(v[i])) f.fail("region", "must hold finite numbers, got " + r.dump());
    }
    if (!(v[0] < v[2] && v[1] < v[3])) f.fail("region", "needs x0 < x1 and y0 < y1, got " + r.dump());
    g.region = sim::Box{v[0], v[1], v[2], v[3]};
  }
  return g;
}

}  // namespace

std::variant<sim::Scene, std::string> parse_scene(const std::string& json_text) {
  std::string why;
  const auto parsed = parse_json(json_text, why);
  if (!parsed) return "scene is not valid JSON: " + why;
  const nlohmann::json& doc = *parsed;
  try {
    Fields f(doc, "");
    f.only({"name", "description", "tick_rate", "steps", "model", "substeps", "broadphase", "arena",
            "friction", "balls", "generators"});
    sim::Scene s;
    s.tick_rate_hz = f.number("tick_rate");
    if (!(s.tick_rate_hz >= 1.0 && s.tick_rate_hz <= 100000.0))
      f.fail("tick_rate", "must be in 1..100000 Hz, got " + nlohmann::json(s.tick_rate_hz).dump());
    s.steps = f.integer("steps");
    if (s.steps < 0) f.fail("steps", "must be >= 0, got " + std::to_string(s.steps));
    s.physics.model = parse_enum(f, "model", sim::Model::continuous, sim::parse_model, "seed, discrete, continuous");
    s.physics.broadphase = parse_enum(f, "broadphase", sim::Broadphase::automatic, sim::parse_broadphase, "auto, pairs, grid");
    const std::int64_t sub = f.integer_or("substeps", 1);
    if (sub < 1 || sub > 1024) f.fail("substeps", "must be in 1..1024, got " + std::to_string(sub));
    s.physics.substeps = static_cast<int>(sub);
    s.physics.friction = f.boolean_or("friction", false);

    Fields a(f.at("arena"), "arena");
    a.only({"width", "height", "boundary"});
    s.arena.width_u = a.number("width");
    s.arena.height_u = a.number("height");
    require_positive(a, "width", s.arena.width_u);
    require_positive(a, "height", s.arena.height_u);
    s.arena.boundary = parse_enum(a, "boundary", sim::Boundary::walls, sim::parse_boundary, "open, walls");

    if (f.has("balls")) {
      const auto& balls = f.at("balls");
      if (!balls.is_array()) f.fail("balls", "must be an array");
      for (std::size_t i = 0; i < balls.size(); ++i) s.balls.push_back(parse_ball(balls[i], "balls[" + std::to_string(i) + "]"));
    }
    if (f.has("generators")) {
      const auto& gens = f.at("generators");
      if (!gens.is_array()) f.fail("generators", "must be an array");
      for (std::size_t i = 0; i < gens.size(); ++i)
        s.generators.push_back(parse_generator(gens[i], "generators[" + std::to_string(i) + "]"));
    }
    if (s.balls.empty() && s.generators.empty()) return std::string("scene has no balls and no generators");
    return s;
  } catch (const FieldError& e) {
    return std::string(e.what());
  }
}

}  // namespace fts::store
