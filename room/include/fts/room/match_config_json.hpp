// MatchConfig from JSON (strict: unknown keys and bad values are errors naming them) and
// the match input log: one JSON line per tick with every player's inputs and commands.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "fts/sim/match.hpp"

namespace fts::room {

// Keys are the MatchConfig field names ("tick_rate_hz", "price_life", ...; "model" is
// "seed" | "discrete" | "continuous"); absent keys keep `base`'s values.
std::variant<sim::MatchConfig, std::string> parse_match_config(const std::string& json_text,
                                                               const sim::MatchConfig& base = {});
nlohmann::json match_config_to_json(const sim::MatchConfig& cfg);
// The keys a client needs (config_fields.hpp marks them), in table order: the welcome
// carries each under the same key (PROTOCOL.md 4.3).
std::vector<std::string> match_config_client_keys();

// One tick of input, e.g.
// {"tick":5,"joins":[{"player":1,"name":"bot1"}],"leaves":[2],
//  "players":[{"id":1,"x":1,"y":-1,"fire":true,"cmd":["buy:mass","ready","play_again"]}]}
// Empty lists, zero moves and false fire are left out.
struct InputLine {
  std::int64_t tick = 0;
  sim::TickInputs inputs;
};
std::string to_input_line(std::int64_t tick, const sim::TickInputs& inputs);
std::variant<InputLine, std::string> parse_input_line(const std::string& line);
// The same from an already parsed line (a record reads each line once, then dispatches).
std::variant<InputLine, std::string> input_line_from_json(const nlohmann::json& line);

}  // namespace fts::room
