// fts-server's settings: flags over environment, errors naming the setting.
#include <catch2/catch.hpp>

#include <map>
#include <set>

#include "app/options.hpp"

using namespace fts::server;

namespace {
EnvLookup env_of(std::map<std::string, std::string> vars) {
  return [vars](const std::string& k) -> std::optional<std::string> {
    auto it = vars.find(k);
    if (it == vars.end()) return std::nullopt;
    return it->second;
  };
}
std::string error_of(std::vector<std::string> args, std::map<std::string, std::string> env = {}) {
  auto r = parse_options(args, env_of(env));
  if (auto* e = std::get_if<OptionError>(&r)) return e->message;
  return "";
}
}  // namespace

TEST_CASE("Server options: defaults, flags and the environment", "[server][options]") {
  auto r = parse_options({}, env_of({}));
  REQUIRE(std::holds_alternative<Options>(r));
  CHECK(std::get<Options>(r).port == 7777);
  CHECK(std::get<Options>(r).tick_rate_hz == 100);

  r = parse_options({"--port", "9000", "--model=discrete"}, env_of({{"FTS_PORT", "8000"}, {"FTS_SEED", "42"}}));
  REQUIRE(std::holds_alternative<Options>(r));
  const auto& o = std::get<Options>(r);
  CHECK(o.port == 9000);  // the flag wins over FTS_PORT
  CHECK(o.seed == 42);    // the environment fills what flags leave
  CHECK(o.model == "discrete");
}

TEST_CASE("Server options: bad values name the flag or variable and the value", "[server][options]") {
  CHECK(error_of({"--port", "70000"}) == R"(--port: must be a port number 0..65535, got "70000")");
  CHECK(error_of({}, {{"FTS_TICK_RATE", "5"}}) == R"(FTS_TICK_RATE: must be 10..1000 Hz, got "5")");
  CHECK(error_of({"--model", "exact"}) == R"(--model: must be seed, discrete or continuous, got "exact")");
  CHECK(error_of({"--colour", "red"}) == "unknown flag --colour (see --help)");
  CHECK(error_of({"--port"}) == "--port: needs a value");
  CHECK(error_of({"stray"}) == R"(unexpected argument "stray" (see --help))");
  // Issue 38: --record and --record-dir go together (room 1 into PATH, the others into
  // DIR/room-<id>), unless PATH would share DIR with the other rooms.
  CHECK_THAT(error_of({"--record", "d/room-2", "--record-dir", "d"}), Catch::StartsWith("--record d/room-2 is inside --record-dir d"));
  CHECK_THAT(error_of({"--record-dir", "d"}, {{"FTS_RECORD", "./d/"}}), Catch::Contains("give a --record outside DIR"));
  CHECK_THAT(error_of({"--record", "d/x/../rooms", "--record-dir", "d/"}), Catch::Contains("is inside --record-dir"));
}

TEST_CASE("Server options: --record and --record-dir together", "[server][options]") {
  for (const auto& [path, dir] : {std::pair{"one", "rooms"}, std::pair{"rooms/room-1", "rooms"},
                                  std::pair{"rooms-1", "rooms"}, std::pair{"../one", "rooms"}}) {
    INFO(path << " beside " << dir);
    auto r = parse_options({"--record", path, "--record-dir", dir}, env_of({}));
    REQUIRE(std::holds_alternative<Options>(r));
    CHECK(std::get<Options>(r).record_path == path);
    CHECK(std::get<Options>(r).record_dir == dir);
  }
}

TEST_CASE("Server options: the command line's forms", "[server][options]") {
  auto options = [](std::vector<std::string> args) {
    auto r = parse_options(args, env_of({}));
    REQUIRE(std::holds_alternative<Options>(r));
    return std::get<Options>(r);
  };
  CHECK(options({"--port=9000"}).port == 9000);
  CHECK(options({"--port", "9000", "--port", "9001"}).port == 9001);  // the last one wins
  CHECK(options({"--help"}).help);
  CHECK(options({"-h"}).help);
  CHECK(options({"--version"}).version);
  CHECK(options({"--seed", "3", "--model", "seed"}).given == std::set<std::string>{"seed", "model"});
  CHECK(error_of({"--seed", "3", "--port"}) == "--port: needs a value");
  CHECK(error_of({"--colour=red"}) == "unknown flag --colour (see --help)");
  CHECK(error_of({"-x"}) == R"(unexpected argument "-x" (see --help))");
}

TEST_CASE("Server options: every row is in the usage text and the reference", "[server][options]") {
  const std::string usage = usage_text();
  const std::string markdown = markdown_text();
  for (const auto& d : option_docs()) {
    INFO(d.flag);
    if (d.hidden) {
      CHECK(usage.find(d.flag) == std::string::npos);
      continue;
    }
    CHECK(usage.find("  " + d.flag + " ") != std::string::npos);
    CHECK(usage.find(d.env) != std::string::npos);
    CHECK(markdown.find("| `" + d.flag) != std::string::npos);
    if (!d.default_value.empty() && d.kind == fts::cli::Kind::value)
      CHECK(usage.find("default " + d.default_value) != std::string::npos);
  }
  CHECK_THAT(usage, Catch::Contains("  --port PORT                 UDP port to listen on (0: any free port) [FTS_PORT, default 7777]"));
  CHECK_THAT(markdown, Catch::Contains("| `--tick-rate HZ` | `FTS_TICK_RATE` | `100` | 10..1000 |"));
  CHECK_THAT(markdown, Catch::Contains("| `--agones on\\|off\\|PORT` | `FTS_AGONES` | `off` |"));
}

TEST_CASE("Server options: --help-markdown and --resume from the environment", "[server][options]") {
  auto r = parse_options({"--help-markdown"}, env_of({}));
  REQUIRE(std::holds_alternative<Options>(r));
  CHECK(std::get<Options>(r).markdown);
  r = parse_options({"--journal-dir", "j"}, env_of({{"FTS_RESUME", "1"}}));
  REQUIRE(std::holds_alternative<Options>(r));
  CHECK(std::get<Options>(r).resume);
  CHECK(error_of({}, {{"FTS_RESUME", "1"}}) == "--resume: needs --journal-dir DIR (where the journals are)");
  CHECK(error_of({"--time-scale", "0.05"}) == R"(--time-scale: must be 0.1..100, got "0.05")");
  CHECK(error_of({"--bind", "localhost"}) == R"(--bind: must be an IPv4 or IPv6 address, got "localhost")");
}

TEST_CASE("Server options: --threads (issue 29)", "[server][options][threads]") {
  auto threads_of = [](std::vector<std::string> args, std::map<std::string, std::string> env) {
    auto r = parse_options(args, env_of(env));
    REQUIRE(std::holds_alternative<Options>(r));
    return std::get<Options>(r).threads;
  };
  CHECK(threads_of({}, {}) == 0);  // every usable core
  CHECK(threads_of({"--threads", "2"}, {}) == 2);
  CHECK(threads_of({}, {{"FTS_THREADS", "1"}}) == 1);
  CHECK(error_of({"--threads", "257"}) == R"(--threads: must be 0..256 (0: every core), got "257")");
  CHECK(error_of({"--threads", "two"}) == R"(--threads: must be 0..256 (0: every core), got "two")");
}
