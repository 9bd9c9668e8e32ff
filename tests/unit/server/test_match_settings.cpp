// fts-server's match configuration: default < --config file < FTS_* variable < flag.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <unistd.h>

#include "app/match_settings.hpp"

using namespace fts;

namespace {

struct ConfigFile {
  std::string path;
  explicit ConfigFile(const std::string& json) {
    path = (std::filesystem::temp_directory_path() /
            ("fts-match-settings-" + std::to_string(::getpid()) + ".json")).string();
    std::ofstream(path) << json;
  }
  ~ConfigFile() { std::filesystem::remove(path); }
};

// Options as fts-server parses them from `args` and `env`, then the resolved config.
std::variant<sim::MatchConfig, std::string> resolve(std::vector<std::string> args,
                                                    std::map<std::string, std::string> env = {}) {
  auto lookup = [env](const std::string& k) -> std::optional<std::string> {
    auto it = env.find(k);
    return it == env.end() ? std::nullopt : std::optional<std::string>(it->second);
  };
  auto parsed = server::parse_options(args, lookup);
  REQUIRE(std::holds_alternative<server::Options>(parsed));
  auto options = std::get<server::Options>(parsed);
  return server::resolve_match_config(options);
}

sim::MatchConfig config_of(std::vector<std::string> args, std::map<std::string, std::string> env = {}) {
  auto r = resolve(std::move(args), std::move(env));
  if (auto* err = std::get_if<std::string>(&r)) FAIL(*err);
  return std::get<sim::MatchConfig>(r);
}

}  // namespace

TEST_CASE("Server config: default < file < environment < flag", "[server][options]") {
  ConfigFile file(R"({"tick_rate_hz": 50, "max_players": 2, "model": "seed"})");

  SECTION("defaults without a file") {
    const auto c = config_of({});
    CHECK(c.tick_rate_hz == 100);
    CHECK(c.max_players == 8);
    CHECK(c.model == sim::Model::continuous);
  }
  SECTION("the file over the defaults (flag defaults do not overwrite it)") {
    const auto c = config_of({"--config", file.path});
    CHECK(c.tick_rate_hz == 50);
    CHECK(c.max_players == 2);
    CHECK(c.model == sim::Model::seed);
  }
  SECTION("the environment over the file") {
    const auto c = config_of({"--config", file.path},
                             {{"FTS_TICK_RATE", "60"}, {"FTS_MAX_PLAYERS", "3"}, {"FTS_MODEL", "discrete"}});
    CHECK(c.tick_rate_hz == 60);
    CHECK(c.max_players == 3);
    CHECK(c.model == sim::Model::discrete);
  }
  SECTION("the config file itself from the environment") {
    CHECK(config_of({}, {{"FTS_CONFIG", file.path}}).max_players == 2);
  }
  SECTION("flags over the environment and the file") {
    const auto c = config_of({"--config", file.path, "--tick-rate", "70", "--max-players", "4", "--model", "continuous"},
                             {{"FTS_TICK_RATE", "60"}, {"FTS_MAX_PLAYERS", "3"}, {"FTS_MODEL", "discrete"}});
    CHECK(c.tick_rate_hz == 70);
    CHECK(c.max_players == 4);
    CHECK(c.model == sim::Model::continuous);
  }
}

TEST_CASE("Server config: the resolved values reach the options the clock and endpoint read", "[server][options]") {
  ConfigFile file(R"({"tick_rate_hz": 50, "max_players": 2, "model": "seed"})");
  auto parsed = server::parse_options({"--config", file.path}, [](const std::string&) { return std::nullopt; });
  auto options = std::get<server::Options>(parsed);
  REQUIRE(std::holds_alternative<sim::MatchConfig>(server::resolve_match_config(options)));
  CHECK(options.tick_rate_hz == 50);
  CHECK(options.max_players == 2);
  CHECK(options.model == "seed");
}

TEST_CASE("Server config: a file the server cannot run is refused, naming it", "[server][options]") {
  auto error_of = [](const std::string& json, std::vector<std::string> args = {}) {
    ConfigFile file(json);
    args.insert(args.begin(), {"--config", file.path});
    auto r = resolve(args);
    return std::holds_alternative<std::string>(r) ? std::get<std::string>(r).substr(file.path.size()) : "ok";
  };
  CHECK(error_of(R"({"tick_rate_hz": 33.5})") == ": tick_rate_hz: fts-server runs 10..1000 whole ticks per second, got 33.5");
  CHECK(error_of(R"({"tick_rate_hz": 5000})") == ": tick_rate_hz: fts-server runs 10..1000 whole ticks per second, got 5000");
  CHECK(error_of(R"({"tick_rate_hz": 33.5})", {"--tick-rate", "40"}) == "ok");  // the flag replaces it
  CHECK_THAT(error_of(R"({"no_such_setting": 1})"), Catch::Contains("no_such_setting"));
  auto missing = resolve({"--config", "/nonexistent/fts.json"});
  REQUIRE(std::holds_alternative<std::string>(missing));
  CHECK(std::get<std::string>(missing) == "--config: cannot read /nonexistent/fts.json");
}
