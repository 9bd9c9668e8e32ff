// Hosting documents that cannot rot: the example server config is loaded through the
// server's own parser and must equal the built-in defaults, the config table names every
// key, and the hosting page's settings section (docs/hosting.md) links the generated flag
// reference and names only flags fts-server has.
#include <catch2/catch.hpp>

#include <cctype>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "app/options.hpp"
#include "fts/room/match_config_json.hpp"

namespace {

std::string read_repo_file(const std::string& relative) {
  std::ifstream in(std::string(FTS_SOURCE_DIR) + "/" + relative);
  INFO("file " << relative);
  REQUIRE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The lines of docs/hosting.md's settings section (up to the next level-2 heading).
std::string hosting_settings_section() {
  const std::string readme = read_repo_file("docs/hosting.md");
  const auto start = readme.find("\n## Ports, settings and the container");
  if (start == std::string::npos) return "";
  const auto end = readme.find("\n## ", start + 1);
  return readme.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

}  // namespace

TEST_CASE("Hosting: the example server config loads and equals the defaults", "[hosting]") {
  const std::string text = read_repo_file("docker/server-config.example.json");
  auto parsed = fts::room::parse_match_config(text);
  if (auto* err = std::get_if<std::string>(&parsed)) FAIL("example config rejected: " << *err);
  const auto& cfg = std::get<fts::sim::MatchConfig>(parsed);
  const auto defaults_json = fts::room::match_config_to_json(fts::sim::MatchConfig{});

  SECTION("it round-trips: parse -> JSON -> parse gives the same JSON") {
    const auto once = fts::room::match_config_to_json(cfg);
    auto again = fts::room::parse_match_config(once.dump());
    REQUIRE(std::holds_alternative<fts::sim::MatchConfig>(again));
    CHECK(fts::room::match_config_to_json(std::get<fts::sim::MatchConfig>(again)) == once);
  }
  SECTION("every setting is present with its default (regenerate with docker/gen-server-config.py)") {
    const auto file_json = nlohmann::json::parse(text);
    INFO("expected example:\n" << defaults_json.dump(2));
    CHECK(file_json.size() == defaults_json.size());
    for (const auto& [key, value] : defaults_json.items()) {
      INFO("key " << key);
      REQUIRE(file_json.contains(key));
      CHECK(file_json.at(key) == value);
    }
    CHECK(fts::room::match_config_to_json(cfg) == defaults_json);
  }
  SECTION("the table beside it documents every key") {
    const std::string table = read_repo_file("docker/server-config.md");
    for (const auto& [key, value] : defaults_json.items()) {
      INFO("key " << key);
      CHECK(table.find("| `" + key + "` | `" + value.dump() + "` |") != std::string::npos);
    }
  }
}

TEST_CASE("Hosting: a config with an unknown key is refused, naming the key", "[hosting]") {
  auto parsed = fts::room::parse_match_config(R"({"tick_rate_hz": 100, "tick_rate": 50})");
  REQUIRE(std::holds_alternative<std::string>(parsed));
  CHECK_THAT(std::get<std::string>(parsed), Catch::Contains("tick_rate"));
  CHECK_THAT(std::get<std::string>(parsed), Catch::Contains("unknown key"));
}

TEST_CASE("Hosting: docs/hosting.md's settings point at the generated flag reference", "[hosting]") {
  // The table itself is docs/flags/fts-server.md, fts-server --help-markdown (the test
  // flags_docs holds it to the program); the hosting page links it and names no flag
  // the table does not have.
  const std::string section = hosting_settings_section();
  REQUIRE_FALSE(section.empty());
  CHECK_THAT(section, Catch::Contains("(flags/fts-server.md)"));
  std::set<std::string> flags;
  for (const auto& d : fts::server::option_docs()) flags.insert(d.flag);
  for (std::size_t at = section.find("`--"); at != std::string::npos; at = section.find("`--", at + 1)) {
    std::size_t end = at + 3;
    while (end < section.size() && (std::isalnum(static_cast<unsigned char>(section[end])) || section[end] == '-')) ++end;
    const std::string flag = section.substr(at + 1, end - at - 1);
    INFO("docs/hosting.md names " << flag);
    CHECK((flags.contains(flag) || flag == "--help"));
  }
}
