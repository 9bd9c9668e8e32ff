// fts-sim: the simulation without a network. Scene mode runs a physics scene and prints
// one JSON report; `--match` plays a headless match (see match_cli.hpp).
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "host/scene_json.hpp"
#include "fts/room/text.hpp"
#include "host/scene_run.hpp"
#include "sim/match_cli.hpp"

namespace {

constexpr const char* kUsage =
    "usage: fts-sim SCENE.json [--model seed|discrete|continuous] [--substeps K]\n"
    "               [--tick-rate HZ] [--steps N] [--broadphase auto|pairs|grid]\n"
    "               [--dump-state FILE] [--check-every K]\n"
    "       fts-sim --match [--players N] [--levels N] [--max-ticks T] [--seed S] [--model M]\n"
    "               [--config FILE] [--inputs FILE] [--record FILE]\n"
    "Scene mode prints one JSON object (see README.md); flags override the scene file.\n";

int usage_error(const std::string& message) {
  std::cerr << "fts-sim: " << message << "\n" << kUsage;
  return 2;
}

int run_scene_mode(const std::vector<std::string>& args) {
  CLI::App app{"", "fts-sim"};
  app.allow_extras();
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  // Each value flag and what its missing value is called.
  const std::vector<std::pair<std::string, std::string>> flags = {
      {"--model", "a value"}, {"--broadphase", "a value"}, {"--substeps", "a value"}, {"--tick-rate", "a value"},
      {"--steps", "a value"}, {"--dump-state", "a file"}, {"--check-every", "a value"}};
  for (const auto& f : flags) app.add_option(f.first);
  std::vector<std::string> scenes;
  app.add_option("scene", scenes);
  try {
    app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 wants them reversed
  } catch (const CLI::ArgumentMismatch&) {
    // Only a flag at the very end lacks its value (any next argument is taken).
    const std::string flag = args.back().substr(0, args.back().find('='));
    for (const auto& [name, needs] : flags)
      if (name == flag) return usage_error(flag + " needs " + needs);
    return usage_error(flag + " needs a value");
  } catch (const CLI::ParseError& e) {
    return usage_error(e.what());
  }
  for (const auto& a : app.remaining()) {
    if (a.rfind("--", 0) == 0) return usage_error("unknown flag " + a);
    scenes.push_back(a);  // e.g. "-": not a flag
  }
  if (scenes.size() > 1) return usage_error("more than one scene file: " + scenes[1]);
  const std::string scene_path = scenes.empty() ? "" : scenes[0];
  auto value = [&](const std::string& flag) -> std::optional<std::string> {
    const CLI::Option* o = app.get_option(flag);
    if (o->count() == 0) return std::nullopt;
    return o->results().back();
  };
  const auto model = value("--model"), broadphase = value("--broadphase"), substeps = value("--substeps"),
             tick_rate = value("--tick-rate"), steps = value("--steps");
  const std::string dump_path = value("--dump-state").value_or("");
  const std::string check_every = value("--check-every").value_or("1");
  if (scene_path.empty()) return usage_error("no scene file given");
  std::ifstream in(scene_path);
  if (!in) return usage_error("cannot read scene file " + scene_path);
  std::stringstream text;
  text << in.rdbuf();
  auto parsed = fts::host::parse_scene(text.str());
  if (auto* err = std::get_if<std::string>(&parsed)) {
    std::cerr << "fts-sim: " << scene_path << ": " << *err << "\n";
    return 1;
  }
  auto scene = std::get<fts::sim::Scene>(parsed);
  if (model) {
    auto m = fts::sim::parse_model(*model);
    if (!m) return usage_error("--model must be seed, discrete or continuous, got " + *model);
    scene.physics.model = *m;
  }
  if (broadphase) {
    auto b = fts::sim::parse_broadphase(*broadphase);
    if (!b) return usage_error("--broadphase must be auto, pairs or grid, got " + *broadphase);
    scene.physics.broadphase = *b;
  }
  if (substeps) {
    auto k = fts::room::to_integer(*substeps);
    if (!k || *k < 1 || *k > 1024) return usage_error("--substeps must be 1..1024, got " + *substeps);
    scene.physics.substeps = static_cast<int>(*k);
  }
  if (tick_rate) {
    auto hz = fts::room::to_number(*tick_rate);
    if (!hz || !(*hz >= 1.0 && *hz <= 100000.0)) return usage_error("--tick-rate must be 1..100000, got " + *tick_rate);
    scene.tick_rate_hz = *hz;
  }
  if (steps) {
    auto n = fts::room::to_integer(*steps);
    if (!n || *n < 0) return usage_error("--steps must be >= 0, got " + *steps);
    scene.steps = *n;
  }
  auto every = fts::room::to_integer(check_every);
  if (!every || *every < 0) return usage_error("--check-every must be >= 0, got " + check_every);

  fts::sim::World world;
  if (auto err = fts::sim::build_world(scene, world)) {
    std::cerr << "fts-sim: " << scene_path << ": " << *err << "\n";
    return 1;
  }
  const auto report = fts::simtool::run_scene(scene, world, *every);
  std::cout << fts::simtool::to_json(report) << "\n";
  if (!dump_path.empty()) {
    nlohmann::json balls = nlohmann::json::array();
    for (const auto& b : world.balls) {
      balls.push_back({{"id", b.id}, {"x", b.pos.x}, {"y", b.pos.y}, {"vx", b.vel.x}, {"vy", b.vel.y},
                       {"r", b.radius}, {"m", b.mass}});
    }
    std::ofstream out(dump_path);
    out << balls.dump() << "\n";
    if (!out) {
      std::cerr << "fts-sim: cannot write " << dump_path << "\n";
      return 1;
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  for (const auto& a : args) {
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (a == "--version") {
      std::cout << "fts-sim 0.1.0\n";
      return 0;
    }
  }
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--match") {
      args.erase(args.begin() + static_cast<std::ptrdiff_t>(i));
      return fts::simtool::run_match_cli(args);
    }
  }
  return run_scene_mode(args);
}
