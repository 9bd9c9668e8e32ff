// The match configuration file and the input log: strict parsing, errors naming the field.
#include <catch2/catch.hpp>

#include "fts/room/match_config_json.hpp"

using namespace fts::sim;
using fts::room::parse_input_line;
using fts::room::parse_match_config;

namespace {

std::string error_of(const std::string& json) {
  auto r = parse_match_config(json);
  if (auto* e = std::get_if<std::string>(&r)) return *e;
  return "";
}

}  // namespace

TEST_CASE("Config: defaults are the rules' numbers and survive a JSON round trip") {
  const MatchConfig d;
  const auto j = fts::room::match_config_to_json(d);
  CHECK(j.at("price_life") == 500);
  CHECK(j.at("model") == "continuous");
  auto r = parse_match_config(j.dump());
  REQUIRE(std::holds_alternative<MatchConfig>(r));
  CHECK(fts::room::match_config_to_json(std::get<MatchConfig>(r)) == j);
}

TEST_CASE("Config: values are read and an unknown key or a bad value is named") {
  auto r = parse_match_config(R"({"tick_rate_hz": 50, "model": "discrete", "price_life": 600, "max_players": 4})");
  REQUIRE(std::holds_alternative<MatchConfig>(r));
  const auto& c = std::get<MatchConfig>(r);
  CHECK(c.tick_rate_hz == 50.0);
  CHECK(c.model == Model::discrete);
  CHECK(c.price_life == 600);
  CHECK(c.max_players == 4);
  CHECK_THAT(error_of(R"({"tick_rat_hz": 50})"), Catch::Contains("tick_rat_hz") && Catch::Contains("unknown key"));
  CHECK_THAT(error_of(R"({"tick_rate_hz": "fast"})"), Catch::Contains("tick_rate_hz"));
  CHECK_THAT(error_of(R"({"tick_rate_hz": 0})"), Catch::Contains("tick_rate_hz"));
  CHECK_THAT(error_of(R"({"model": "warp"})"), Catch::Contains("model") && Catch::Contains("warp"));
  CHECK_THAT(error_of(R"({"price_life": 1.5})"), Catch::Contains("price_life"));
  CHECK_THAT(error_of(R"({"price_life": -3})"), Catch::Contains("prices"));
  CHECK_THAT(error_of(R"({"max_players": 0})"), Catch::Contains("max_players"));
  CHECK_THAT(error_of(R"([1, 2])"), Catch::Contains("object"));
  CHECK_THAT(error_of(R"({"coin_cap": 1)"), Catch::Contains("invalid JSON"));
  // A key twice is refused naming it; nlohmann alone kept the last one (issue 36 point 9).
  CHECK(error_of(R"({"tick_rate_hz": 50, "model": "seed", "tick_rate_hz": 100})") ==
        R"(match config: invalid JSON: key "tick_rate_hz" appears twice in one object)");
}

TEST_CASE("Input log: one line per tick round-trips every input and command") {
  TickInputs in;
  in.joins = {{1, "ann"}, {2, "bob"}};
  in.leaves = {3};
  in.away = {4};
  in.back = {5};
  in.quit = {6};  // regression: quits were not recorded, so a replay diverged after one
  in.players.push_back({1, {1, -1, true}, {{CommandKind::buy, "mass"}, {CommandKind::ready, {}}}});
  in.players.push_back({2, {0, 1, false}, {{CommandKind::play_again, {}}}});
  const std::string line = fts::room::to_input_line(42, in);
  CHECK(line.find('\n') == std::string::npos);
  auto r = parse_input_line(line);
  REQUIRE(std::holds_alternative<fts::room::InputLine>(r));
  const auto& got = std::get<fts::room::InputLine>(r);
  CHECK(got.tick == 42);
  CHECK(fts::room::to_input_line(got.tick, got.inputs) == line);
  REQUIRE(got.inputs.players.size() == 2);
  CHECK(got.inputs.players[0].input.move_y == -1);
  CHECK(got.inputs.players[0].commands[0].item == "mass");
  CHECK(got.inputs.away == std::vector<PlayerId>{4});
  CHECK(got.inputs.back == std::vector<PlayerId>{5});
  CHECK(got.inputs.quit == std::vector<PlayerId>{6});
}

TEST_CASE("Input log: a bad line names the field") {
  auto err = [](const std::string& l) {
    auto r = parse_input_line(l);
    auto* e = std::get_if<std::string>(&r);
    return e ? *e : std::string();
  };
  CHECK_THAT(err(R"({"tick": 1, "players": [{"id": 1, "x": 2}]})"), Catch::Contains("players[0].x"));
  CHECK(err(R"({"tick": 1, "players": [{"id": 1, "id": 2}]})") ==
        R"(input line: invalid JSON: key "id" appears twice in one object (at players[0].id))");
  CHECK_THAT(err(R"({"tick": 1, "players": [{"id": 1, "cmd": ["dance"]}]})"), Catch::Contains("dance"));
  CHECK_THAT(err(R"({"tick": -1})"), Catch::Contains("tick"));
  CHECK_THAT(err(R"({"tick": 1, "moves": []})"), Catch::Contains("moves"));
  CHECK_THAT(err(R"({"tick": 1, "joins": [{"player": 0, "name": "x"}]})"), Catch::Contains("joins[0].player"));
}
