// libFuzzer target: every byte string is a physics scene file (fts-sim SCENE.json), read
// by store::parse_scene. Properties: nothing escapes (a bad scene is a message); what
// parses is written back as a scene file (below, from the fields of sim::Scene) that
// parses to the same scene; a small scene builds and steps as fts-sim runs it.
// Built and run by .ci/fuzz.sh (clang, -DFTS_FUZZ=ON).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_check.hpp"
#include "store/scene_json.hpp"
#include "store/scene_run.hpp"

using namespace fts;
using fuzz::check;
using fuzz::fail;

namespace {

nlohmann::json scene_json(const sim::Scene& s) {
  nlohmann::json j = {{"tick_rate", s.tick_rate_hz},
                      {"steps", s.steps},
                      {"model", std::string(sim::to_string(s.physics.model))},
                      {"substeps", s.physics.substeps},
                      {"broadphase", std::string(sim::to_string(s.physics.broadphase))},
                      {"friction", s.physics.friction},
                      {"arena",
                       {{"width", s.arena.width_u},
                        {"height", s.arena.height_u},
                        {"boundary", std::string(sim::to_string(s.arena.boundary))}}}};
  auto& balls = j["balls"] = nlohmann::json::array();
  for (const auto& b : s.balls) balls.push_back({{"x", b.x}, {"y", b.y}, {"vx", b.vx}, {"vy", b.vy}, {"r", b.r}, {"m", b.m}});
  auto& gens = j["generators"] = nlohmann::json::array();
  for (const auto& g : s.generators) {
    nlohmann::json o = {{"count", g.count}, {"radius", g.radius}, {"mass", g.mass},
                        {"speed", g.speed_u_per_s}, {"seed", g.seed}, {"overlap", g.allow_overlap}};
    if (g.region) o["region"] = {g.region->x0, g.region->y0, g.region->x1, g.region->y1};
    gens.push_back(std::move(o));
  }
  return j;
}

bool same(const sim::Scene& a, const sim::Scene& b) {
  auto ball = [](const sim::BallSpec& x, const sim::BallSpec& y) {
    return x.x == y.x && x.y == y.y && x.vx == y.vx && x.vy == y.vy && x.r == y.r && x.m == y.m;
  };
  auto gen = [](const sim::Generator& x, const sim::Generator& y) {
    const bool region = x.region.has_value() == y.region.has_value() &&
                        (!x.region || (x.region->x0 == y.region->x0 && x.region->y0 == y.region->y0 &&
                                       x.region->x1 == y.region->x1 && x.region->y1 == y.region->y1));
    return x.count == y.count && x.radius == y.radius && x.mass == y.mass && x.speed_u_per_s == y.speed_u_per_s &&
           x.seed == y.seed && x.allow_overlap == y.allow_overlap && region;
  };
  return a.tick_rate_hz == b.tick_rate_hz && a.steps == b.steps && a.physics.model == b.physics.model &&
         a.physics.substeps == b.physics.substeps && a.physics.broadphase == b.physics.broadphase &&
         a.physics.friction == b.physics.friction && a.arena.width_u == b.arena.width_u &&
         a.arena.height_u == b.arena.height_u && a.arena.boundary == b.arena.boundary &&
         std::equal(a.balls.begin(), a.balls.end(), b.balls.begin(), b.balls.end(), ball) &&
         std::equal(a.generators.begin(), a.generators.end(), b.generators.begin(), b.generators.end(), gen);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    auto parsed = store::parse_scene(text);
    if (const auto* err = std::get_if<std::string>(&parsed)) {
      check(!err->empty(), "an error says what is wrong");
      return 0;
    }
    sim::Scene& scene = std::get<sim::Scene>(parsed);
    check(!scene.balls.empty() || !scene.generators.empty(), "a scene has bodies");

    const std::string again_text = scene_json(scene).dump();
    auto again = store::parse_scene(again_text);
    if (const auto* err = std::get_if<std::string>(&again)) fail("the written-back scene is refused: " + *err);
    if (!same(scene, std::get<sim::Scene>(again))) fail("the scene changed through JSON: " + again_text);

    // fts-sim's run, kept small: at most 16 bodies, 4 ticks of at most 16 sub-steps.
    std::int64_t bodies = static_cast<std::int64_t>(scene.balls.size());
    for (const auto& g : scene.generators) bodies += g.count;
    if (bodies > 16) return 0;
    scene.steps = std::min<std::int64_t>(scene.steps, 4);
    scene.physics.substeps = std::min(scene.physics.substeps, 16);
    sim::World world;
    if (const auto err = sim::build_world(scene, world)) {
      check(!err->empty(), "a build error says what is wrong");
      return 0;
    }
    const auto report = simtool::run_scene(scene, world);
    check(report.steps == scene.steps, "the run steps the scene's ticks");
    (void)simtool::to_json(report);
  } catch (const std::exception& e) {
    fail(std::string("exception escaped: ") + e.what());
  }
  return 0;
}
