// The match configuration fts-server runs, from four sources in rising precedence:
// built-in defaults < the --config file < FTS_* variables < flags. The options a config
// key overlaps are the rows of app/option_table.hpp with a config key.
#pragma once

#include <string>
#include <variant>

#include "app/options.hpp"
#include "fts/sim/config.hpp"

namespace fts::server {

// Reads options.config_path (if any) and applies the tick rate, player limit and model
// that a flag or variable gave (options.given) over it. The result is written back into
// `options` too, whose tick rate and player limit the clock and the endpoint read.
// On failure: a message naming the file or setting and the value.
std::variant<sim::MatchConfig, std::string> resolve_match_config(Options& options);

}  // namespace fts::server
