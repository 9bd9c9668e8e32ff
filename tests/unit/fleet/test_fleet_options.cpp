// The fleet's settings: --agones (and Agones' own AGONES_SDK_HTTP_PORT), --metrics.
#include <catch2/catch.hpp>

#include <map>

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
Options parsed(std::vector<std::string> args, std::map<std::string, std::string> env = {}) {
  auto r = parse_options(args, env_of(env));
  if (auto* e = std::get_if<OptionError>(&r)) FAIL("unexpected error: " << e->message);
  return std::get<Options>(r);
}
std::string error_of(std::vector<std::string> args, std::map<std::string, std::string> env = {}) {
  auto r = parse_options(args, env_of(env));
  if (auto* e = std::get_if<OptionError>(&r)) return e->message;
  return "";
}
}  // namespace

TEST_CASE("Fleet options: Agones is off unless asked for or its sidecar's port is set", "[fleet][options]") {
  CHECK(parsed({}).agones_port == 0);
  CHECK(parsed({"--agones", "on"}).agones_port == 9358);
  CHECK(parsed({"--agones", "9400"}).agones_port == 9400);
  CHECK(parsed({}, {{"AGONES_SDK_HTTP_PORT", "9359"}}).agones_port == 9359);
  CHECK(parsed({"--agones", "on"}, {{"AGONES_SDK_HTTP_PORT", "9359"}}).agones_port == 9359);
  CHECK(parsed({"--agones", "off"}, {{"AGONES_SDK_HTTP_PORT", "9359"}}).agones_port == 0);
  CHECK(parsed({}, {{"FTS_AGONES", "off"}, {"AGONES_SDK_HTTP_PORT", "9359"}}).agones_port == 0);
  CHECK(error_of({"--agones", "yes"}) == R"(--agones: must be on, off or the SDK's HTTP port 1..65535, got "yes")");
  CHECK(error_of({}, {{"AGONES_SDK_HTTP_PORT", "x"}}) ==
        R"(AGONES_SDK_HTTP_PORT: must be on, off or the SDK's HTTP port 1..65535, got "x")");
  CHECK(error_of({"--agones-health-ms", "10"}) == R"(--agones-health-ms: must be 100..60000 ms, got "10")");
  CHECK(parsed({"--drain-grace-ms", "0"}).drain_grace_ms == 0);
}

TEST_CASE("Fleet options: --metrics is ADDR:PORT, off by default, never the game port", "[fleet][options]") {
  CHECK(parsed({}).metrics_address.empty());
  CHECK(parsed({"--metrics", "127.0.0.1:9100"}).metrics_address == "127.0.0.1:9100");
  CHECK(parsed({"--metrics", ""}).metrics_address.empty());
  CHECK(parsed({}, {{"FTS_METRICS", "0.0.0.0:9100"}}).metrics_address == "0.0.0.0:9100");
  CHECK(error_of({"--metrics", "9100"}).rfind("--metrics: must be ADDR:PORT", 0) == 0);
  CHECK(error_of({"--metrics", "localhost:9100"}).rfind("--metrics: must be ADDR:PORT", 0) == 0);
  CHECK(error_of({"--metrics", "127.0.0.1:0"}).rfind("--metrics: must be ADDR:PORT", 0) == 0);
  CHECK(error_of({"--port", "9100", "--metrics", "127.0.0.1:9100"}) ==
        R"(--metrics: must not be the game port 9100, got "127.0.0.1:9100")");
}
