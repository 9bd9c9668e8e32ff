#include "app/match_settings.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "app/game_host.hpp"
#include "fts/protocol/welcome_size.hpp"
#include "fts/room/match_config_json.hpp"

namespace fts::server {

std::variant<sim::MatchConfig, std::string> resolve_match_config(Options& options) {
  sim::MatchConfig config;
  if (!options.config_path.empty()) {
    std::ifstream in(options.config_path);
    if (!in) return "--config: cannot read " + options.config_path;
    std::stringstream text;
    text << in.rdbuf();
    auto c = room::parse_match_config(text.str());
    if (auto* err = std::get_if<std::string>(&c)) return options.config_path + ": " + *err;
    config = std::get<sim::MatchConfig>(c);
    // The server's clock runs whole ticks per second, in the range --tick-rate allows.
    const double hz = config.tick_rate_hz;
    if (!options.given.contains("tick-rate") && (hz != std::floor(hz) || hz < 10 || hz > 1000)) {
      std::ostringstream v;
      v << hz;
      return options.config_path + ": tick_rate_hz: fts-server runs 10..1000 whole ticks per second, got " + v.str();
    }
  }
  if (options.given.contains("tick-rate")) config.tick_rate_hz = options.tick_rate_hz;
  if (options.given.contains("max-players")) config.max_players = options.max_players;
  if (options.given.contains("model")) config.model = *sim::parse_model(options.model);
  if (auto err = sim::validate(config); !err.empty()) return "configuration: " + err;
  options.tick_rate_hz = static_cast<std::uint32_t>(config.tick_rate_hz);
  options.max_players = static_cast<std::uint32_t>(config.max_players);
  options.model = std::string(sim::to_string(config.model));
  // The welcome carries the configuration's client fields (issue 36) and is never larger
  // than the hello it answers: numbers with many digits in all of them would not fit.
  const std::size_t welcome = protocol::largest_welcome_bytes(make_endpoint_config(options, config, {}).settings);
  if (welcome > protocol::kMinHelloBytes)
    return "configuration: the welcome would be " + std::to_string(welcome) + " bytes, more than the " +
           std::to_string(protocol::kMinHelloBytes) +
           " of a hello it answers (PROTOCOL.md 5.1): write the fields it carries (4.3: tick rate, arena, "
           "frame, friction, shop factors) with fewer digits";
  return config;
}

}  // namespace fts::server
