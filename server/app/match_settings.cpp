#include "app/match_settings.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "app/game_host.hpp"
#include "app/option_table.hpp"
#include "fts/protocol/welcome_size.hpp"
#include "fts/room/match_config_json.hpp"

namespace fts::server {

namespace {

// A config value as an option's text: "seed", "50", "33.5" (a whole number without ".0").
std::string option_text(const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) {
    const double d = v.get<double>();
    if (d == std::floor(d) && std::fabs(d) < 1e15) return std::to_string(static_cast<long long>(d));
  }
  return v.dump();
}

// An option's text as a config value: a number when it reads as one.
nlohmann::json config_value(const std::string& text) {
  auto j = nlohmann::json::parse(text, nullptr, false);
  return j.is_number() ? j : nlohmann::json(text);
}

}  // namespace

std::variant<sim::MatchConfig, std::string> resolve_match_config(Options& options) {
  // The option rows with a config key (kOptionTable: --tick-rate, --max-players, --model)
  // are the overlap: the file's value holds unless the option was given, and the result
  // goes back into the option, which the clock and the endpoint read.
  sim::MatchConfig config;
  if (!options.config_path.empty()) {
    std::ifstream in(options.config_path);
    if (!in) return "--config: cannot read " + options.config_path;
    std::stringstream text;
    text << in.rdbuf();
    auto c = room::parse_match_config(text.str());
    if (auto* err = std::get_if<std::string>(&c)) return options.config_path + ": " + *err;
    config = std::get<sim::MatchConfig>(c);
    // The file's value must be one the option accepts (the server's clock runs whole
    // ticks per second, in the range --tick-rate allows), unless the option replaces it.
    const auto file = room::match_config_to_json(config);
    std::string refused;
    Options probe = options;
    cli::for_each_config_row(kOptionTable, probe, [&](const cli::RowInfo& row, const std::string&, auto set) {
      const std::string v = option_text(file.at(row.config_key));
      if (refused.empty() && !options.given.contains(row.flag.substr(2)) && !set(v))
        refused = options.config_path + ": " + row.config_key + ": " + row.config_want + ", got " + v;
    });
    if (!refused.empty()) return refused;
  }
  auto json = room::match_config_to_json(config);
  cli::for_each_config_row(kOptionTable, options, [&](const cli::RowInfo& row, const std::string& value, auto) {
    if (options.given.contains(row.flag.substr(2))) json[row.config_key] = config_value(value);
  });
  auto merged = room::parse_match_config(json.dump());
  if (auto* err = std::get_if<std::string>(&merged)) return "configuration: " + *err;
  config = std::get<sim::MatchConfig>(merged);
  if (auto err = sim::validate(config); !err.empty()) return "configuration: " + err;
  json = room::match_config_to_json(config);
  std::string unset;
  cli::for_each_config_row(kOptionTable, options, [&](const cli::RowInfo& row, const std::string&, auto set) {
    if (!set(option_text(json.at(row.config_key))) && unset.empty())
      unset = "configuration: " + row.config_key + ": " + row.config_want + ", got " + json.at(row.config_key).dump();
  });
  if (!unset.empty()) return unset;
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
