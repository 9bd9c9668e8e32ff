// Scene files: a bad scene names the field and the value; a good one builds.
#include <catch2/catch.hpp>

#include "store/scene_json.hpp"

using fts::store::parse_scene;

namespace {
std::string error_of(const std::string& text) {
  auto r = parse_scene(text);
  if (auto* e = std::get_if<std::string>(&r)) return *e;
  return "";
}
const std::string kArena = R"("arena": {"width": 100, "height": 100, "boundary": "walls"})";
}  // namespace

TEST_CASE("Scene files: a valid scene parses with its settings", "[scene]") {
  auto r = parse_scene(R"({"tick_rate": 50, "steps": 7, "model": "discrete", "substeps": 4, )" + kArena +
                       R"(, "friction": true, "balls": [{"x": 1, "y": 2, "vx": 3, "vy": 4, "r": 1, "m": 2}]})");
  REQUIRE(std::holds_alternative<fts::sim::Scene>(r));
  const auto& s = std::get<fts::sim::Scene>(r);
  CHECK(s.tick_rate_hz == 50);
  CHECK(s.steps == 7);
  CHECK(s.physics.model == fts::sim::Model::discrete);
  CHECK(s.physics.substeps == 4);
  CHECK(s.physics.friction);
  REQUIRE(s.balls.size() == 1);
  CHECK(s.balls[0].vy == 4);
}

TEST_CASE("Scene files: errors name the field and the value", "[scene]") {
  const std::string ball = R"("balls": [{"x": 1, "y": 2, "r": 1, "m": 1}])";
  CHECK(error_of(R"({"steps": 1, )" + kArena + ", " + ball + "}") == "tick_rate: missing");
  CHECK(error_of(R"({"tick_rate": 100, "steps": 1, "colour": "red", )" + kArena + ", " + ball + "}") ==
        R"(colour: unknown key (value "red"))");
  CHECK(error_of(R"({"tick_rate": 100, "steps": 1, )" + kArena +
                 R"(, "balls": [{"x": 1, "y": 2, "r": -1, "m": 1}]})") == "balls[0].r: must be > 0, got -1.0");
  CHECK(error_of(R"({"tick_rate": 100, "steps": 1, )" + kArena +
                 R"(, "balls": [{"x": 1, "y": 2, "r": 1, "m": 0}]})") == "balls[0].m: must be > 0, got 0.0");
  CHECK(error_of(R"({"tick_rate": 100, "steps": 1, "model": "exact", )" + kArena + ", " + ball + "}") ==
        R"(model: must be one of seed, discrete, continuous, got "exact")");
  CHECK(error_of(R"({"tick_rate": 100, "steps": 1, )" + kArena +
                 R"(, "balls": [{"x": "left", "y": 2, "r": 1, "m": 1}]})") ==
        R"(balls[0].x: must be a number, got "left")");
  // A key twice, at any depth, is refused naming it (nlohmann kept the last one).
  CHECK(error_of(R"({"tick_rate": 100, "tick_rate": 50, "steps": 1, )" + kArena + ", " + ball + "}") ==
        R"(scene is not valid JSON: key "tick_rate" appears twice in one object)");
  CHECK(error_of(R"({"tick_rate": 100, "steps": 1, )" + kArena +
                 R"(, "balls": [{"x": 1, "y": 2, "r": 1, "m": 1, "r": 9}]})") ==
        R"(scene is not valid JSON: key "r" appears twice in one object (at balls[0].r))");
  // JSON has no NaN literal: the parser's message says where it stopped.
  CHECK(error_of(R"({"tick_rate": NaN})").find("not valid JSON") != std::string::npos);
  CHECK(error_of(R"({"tick_rate": 100, "steps": 1, )" + kArena +
                 R"(, "generators": [{"count": 5, "radius": 0, "mass": 1}]})") ==
        "generators[0].radius: must be > 0, got 0.0");
}

TEST_CASE("Scene files: an impossible placement is an error naming the generator", "[scene]") {
  auto r = parse_scene(R"({"tick_rate": 100, "steps": 1, )" + kArena +
                       R"(, "generators": [{"count": 1000, "radius": 5, "mass": 1}]})");
  REQUIRE(std::holds_alternative<fts::sim::Scene>(r));
  fts::sim::World w;
  auto err = fts::sim::build_world(std::get<fts::sim::Scene>(r), w);
  REQUIRE(err.has_value());
  CHECK(err->rfind("generators[0]: impossible placement", 0) == 0);
}
