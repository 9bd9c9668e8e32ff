// libFuzzer target: every byte string is a match config file (fts-server --config, and
// the "config" of a journal's or a record's header), read by room::parse_match_config.
// Properties: nothing escapes (a bad file is a "match config: ..." message); what parses
// passes sim::validate, re-serialises (match_config_to_json) to text that parses to the
// same config, and starts a match that steps a few ticks with a player in it.
// Built and run by .ci/fuzz.sh (clang, -DFTS_FUZZ=ON).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "fts/room/match_config_json.hpp"
#include "fts/sim/match.hpp"
#include "fuzz_check.hpp"

using namespace fts;
using fuzz::check;
using fuzz::fail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    auto parsed = room::parse_match_config(text);
    if (const auto* err = std::get_if<std::string>(&parsed)) {
      check(err->rfind("match config: ", 0) == 0 && err->size() > 14, "an error says what is wrong");
      return 0;
    }
    const sim::MatchConfig& cfg = std::get<sim::MatchConfig>(parsed);
    check(sim::validate(cfg).empty(), "a config that parses is valid");

    const nlohmann::json once = room::match_config_to_json(cfg);
    auto again = room::parse_match_config(once.dump());
    if (const auto* err = std::get_if<std::string>(&again)) fail("the re-serialised config is refused: " + *err);
    if (room::match_config_to_json(std::get<sim::MatchConfig>(again)) != once)
      fail("the config changed through JSON: " + once.dump());

    // What the server does with it: a match, a player joining, a few ticks of play.
    std::uint64_t seed = 1;
    for (std::size_t i = 0; i < size && i < 8; ++i) seed = seed * 131 + data[i];
    sim::MatchState m = sim::make_match(cfg, seed);
    sim::TickInputs join;
    join.joins.push_back({1, "fuzz"});
    (void)sim::step(m, join);
    for (int t = 0; t < 4; ++t) {
      sim::TickInputs in;
      sim::PlayerTick p;
      p.player = 1;
      p.input.move_x = static_cast<std::int8_t>(t % 3 - 1);
      p.input.move_y = 1;
      p.input.fire = t == 2;
      if (t == 1) p.commands.push_back({sim::CommandKind::ready, {}});
      in.players.push_back(p);
      (void)sim::step(m, in);
    }
    (void)sim::match_hash(m);
  } catch (const std::exception& e) {
    fail(std::string("exception escaped: ") + e.what());
  }
  return 0;
}
