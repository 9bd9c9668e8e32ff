// ARCHITECTURE.md "Determinism rules": a recorded input log replays bit-identically. A
// match of bots is written as a record's input lines (fts/room/match_config_json.hpp),
// each line read back and stepped: the state hash is the live one at every tick, in each
// physics model. (Same seed, same hash: unit/match/test_determinism.cpp.)
#include <catch2/catch.hpp>

#include "../match/match_test_util.hpp"
#include "fts/room/match_config_json.hpp"
#include "fts/sim/bot_player.hpp"

using namespace fts::sim;
using namespace fts::test;

TEST_CASE("Input lines: a recorded input log replays bit-identically", "[room][record]") {
  for (Model m : {Model::continuous, Model::discrete, Model::seed}) {
    MatchConfig cfg;
    cfg.model = m;
    std::vector<std::string> lines;
    std::vector<std::uint64_t> hashes;
    MatchState live = make_match(cfg, 11);
    for (int t = 0; t < 2500; ++t) {
      TickInputs in;
      if (t == 0) in = joins(3);
      for (const Player& p : live.players) in.players.push_back(bot_tick(live, p.id));
      lines.push_back(fts::room::to_input_line(live.tick, in));
      step(live, in);
      hashes.push_back(match_hash(live));
    }
    MatchState s = make_match(cfg, 11);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      auto parsed = fts::room::parse_input_line(lines[i]);
      REQUIRE(std::holds_alternative<fts::room::InputLine>(parsed));
      const auto& line = std::get<fts::room::InputLine>(parsed);
      REQUIRE(line.tick == s.tick);
      step(s, line.inputs);
      INFO("model " << to_string(m) << ", tick " << i);
      REQUIRE(match_hash(s) == hashes[i]);
    }
  }
}
