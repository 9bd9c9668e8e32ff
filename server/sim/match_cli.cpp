#include "sim/match_cli.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "fts/sim/bot_player.hpp"
#include "fts/sim/match.hpp"
#include "fts/room/match_config_json.hpp"
#include "fts/room/record.hpp"
#include "fts/room/text.hpp"

namespace fts::simtool {
namespace {

constexpr const char* kMatchUsage =
    "usage: fts-sim --match [--players N] [--levels N] [--max-ticks T] [--seed S] [--model M]\n"
    "                       [--tick-rate HZ] [--config FILE] [--inputs FILE] [--record FILE] [--events]\n";

int usage(const std::string& msg) {
  std::cerr << "fts-sim --match: " << msg << "\n" << kMatchUsage;
  return 2;
}


nlohmann::json event_json(std::int64_t tick, const sim::Event& event) {
  nlohmann::json j = {{"tick", tick}, {"event", sim::to_string(sim::kind_of(event))}};
  auto player = [&](sim::PlayerId id) {
    if (id) j["player"] = id;
  };
  std::visit(sim::Overloaded{
                 [&](const sim::Joined& e) { player(e.player); j["name"] = e.name; },
                 [&](const sim::JoinRefused& e) { player(e.player); j["reason"] = e.reason; },
                 [&](const sim::Left& e) { player(e.player); },
                 [&](const sim::LevelStarted& e) { j["level"] = e.level; j["restart"] = e.restart; },
                 [&](const sim::EnemyDefeated& e) { player(e.player); j["enemy"] = e.enemy; j["coins"] = e.coins; },
                 [&](const sim::PlayerFell& e) { player(e.player); j["lives_left"] = e.lives_left; },
                 [&](const sim::PlayerRespawned& e) { player(e.player); },
                 [&](const sim::LevelComplete& e) { j["level"] = e.level; },
                 [&](const sim::Purchased& e) {
                   player(e.player);
                   j["item"] = e.asked; j["ok"] = e.ok; j["price"] = e.price; j["coins_after"] = e.coins_after;
                   if (!e.ok) j["reason"] = sim::to_string(e.reason);
                 },
                 [&](const sim::RocketFired& e) { player(e.player); j["rocket"] = e.rocket; },
                 [&](const sim::GameOver&) {},
                 [&](const sim::InterestPaid& e) { player(e.player); },
             },
             event);
  return j;
}

struct Tally {
  std::vector<std::int64_t> level_clear_ticks;
  std::int64_t restarts = 0, falls = 0, defeats = 0, untouched = 0, refusals = 0;
  void add(const sim::MatchState& s, const std::vector<sim::Event>& events) {
    for (const auto& event : events) {
      std::visit(sim::Overloaded{
                     [&](const sim::LevelComplete&) { level_clear_ticks.push_back(s.tick); },
                     [&](const sim::LevelStarted& e) { restarts += e.restart ? 1 : 0; },
                     [&](const sim::PlayerFell&) { ++falls; },
                     [&](const sim::EnemyDefeated& e) { ++defeats; untouched += e.player ? 0 : 1; },
                     [&](const sim::Purchased& e) { refusals += e.ok ? 0 : 1; },
                     [](const auto&) {},
                 },
                 event);
    }
  }
};

}  // namespace

int run_match_cli(const std::vector<std::string>& args) {
  std::int64_t players = 1, levels = 5, max_ticks = 1'000'000, seed = 1;
  struct IntFlag {
    const char* flag;
    std::int64_t* out;
    std::int64_t lo, hi;
    const char* message;  // for a missing or bad value
  };
  const IntFlag int_flags[] = {{"--players", &players, 1, 64, "--players must be 1..64"},
                               {"--levels", &levels, 0, 1'000'000, "--levels must be 0..1000000"},
                               {"--max-ticks", &max_ticks, 0, 1'000'000'000'000, "--max-ticks must be >= 0"},
                               {"--seed", &seed, 0, INT64_MAX, "--seed must be >= 0"}};
  const std::pair<const char*, const char*> text_flags[] = {
      {"--model", "--model needs a value"}, {"--tick-rate", "--tick-rate needs a value"},
      {"--config", "--config needs a file"}, {"--inputs", "--inputs needs a file"},
      {"--record", "--record needs a file"}};
  CLI::App app{"", "fts-sim --match"};
  app.set_help_flag();
  app.allow_extras();
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  for (const auto& f : int_flags) app.add_option(f.flag);
  for (const auto& f : text_flags) app.add_option(f.first);
  const CLI::Option* events = app.add_flag("--events");
  try {
    app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 wants them reversed
  } catch (const CLI::ArgumentMismatch&) {
    // Only a flag at the very end lacks its value (any next argument is taken).
    const std::string flag = args.back().substr(0, args.back().find('='));
    for (const auto& f : int_flags)
      if (flag == f.flag) return usage(f.message);
    for (const auto& [name, message] : text_flags)
      if (flag == name) return usage(message);
    return usage(flag + " needs a value");
  } catch (const CLI::ParseError& e) {
    return usage(e.what());
  }
  if (!app.remaining().empty()) return usage("unknown argument " + app.remaining().front());
  auto value = [&](const std::string& flag) -> std::optional<std::string> {
    const CLI::Option* o = app.get_option(flag);
    if (o->count() == 0) return std::nullopt;
    return o->results().back();
  };
  for (const auto& f : int_flags) {
    if (const auto v = value(f.flag)) {
      const auto n = room::to_integer(*v);
      if (!n || *n < f.lo || *n > f.hi) return usage(f.message);
      *f.out = *n;
    }
  }
  const bool print_events = events->count() > 0;
  const auto model = value("--model"), tick_rate = value("--tick-rate"), config_path = value("--config"),
             inputs_path = value("--inputs"), record_path = value("--record");

  sim::MatchConfig cfg;
  if (config_path) {
    std::ifstream in(*config_path);
    if (!in) return usage("cannot read " + *config_path);
    std::stringstream text;
    text << in.rdbuf();
    auto parsed = room::parse_match_config(text.str());
    if (auto* err = std::get_if<std::string>(&parsed)) {
      std::cerr << "fts-sim: " << *config_path << ": " << *err << "\n";
      return 1;
    }
    cfg = std::get<sim::MatchConfig>(parsed);
  }
  if (model) {
    auto m = sim::parse_model(*model);
    if (!m) return usage("--model must be seed, discrete or continuous, got " + *model);
    cfg.model = *m;
  }
  if (tick_rate) {
    auto hz = room::to_integer(*tick_rate);
    if (!hz || *hz < 1 || *hz > 10000) return usage("--tick-rate must be 1..10000 (integer Hz)");
    cfg.tick_rate_hz = static_cast<double>(*hz);
  }
  if (players > cfg.max_players) return usage("--players exceeds max_players");
  if (const std::string err = sim::validate(cfg); !err.empty()) return usage("config: " + err);

  std::ofstream record;
  if (record_path) {
    record.open(*record_path);
    if (!record) return usage("cannot write " + *record_path);
  }
  sim::MatchState s = sim::make_match(cfg, static_cast<std::uint64_t>(seed));
  Tally tally;
  auto run_tick = [&](const sim::TickInputs& in) {
    if (record) record << room::to_input_line(s.tick, in) << "\n";
    const std::int64_t t = s.tick;
    auto events = sim::step(s, in).events;
    tally.add(s, events);
    if (print_events)
      for (const auto& e : events) std::cerr << event_json(t, e).dump() << "\n";
  };

  std::int64_t hashes_checked = -1;
  if (inputs_path) {
    std::error_code ec;
    const bool journal = std::filesystem::is_directory(*inputs_path, ec);
    std::ifstream in;
    if (!journal) {
      in.open(*inputs_path);
      if (!in) return usage("cannot read " + *inputs_path);
    }
    bool history = journal;
    if (!journal && in.peek() == '{') {
      std::string first;
      std::getline(in, first);
      in.seekg(0);
      history = first.find("\"fts_record\"") != std::string::npos;
    }
    if (history) {
      // A server's history (a journal directory or a record): its own seed and config,
      // every hash checked; the input lines that follow are none.
      in.setstate(std::ios::eofbit);
      auto r = room::replay_history(*inputs_path);
      if (auto* err = std::get_if<std::string>(&r)) {
        std::cerr << "fts-sim: replay of " << *inputs_path << " FAILED: " << *err << "\n";
        return 1;
      }
      auto& rep = std::get<room::ReplayReport>(r);
      hashes_checked = rep.hashes_checked;
      s = std::move(rep.state);
      cfg = s.cfg;
      max_ticks = s.tick;
    }
    std::string line;
    std::int64_t line_no = 0;
    while (std::getline(in, line) && s.tick < max_ticks) {
      ++line_no;
      if (line.empty()) continue;
      auto parsed = room::parse_input_line(line);
      if (auto* err = std::get_if<std::string>(&parsed)) {
        std::cerr << "fts-sim: " << *inputs_path << ":" << line_no << ": " << *err << "\n";
        return 1;
      }
      const auto& il = std::get<room::InputLine>(parsed);
      if (il.tick < s.tick) {
        std::cerr << "fts-sim: " << *inputs_path << ":" << line_no << ": tick " << il.tick
                  << " is before the match's tick " << s.tick << "\n";
        return 1;
      }
      while (s.tick < il.tick && s.tick < max_ticks) run_tick({});
      if (s.tick < max_ticks) run_tick(il.inputs);
    }
  } else {
    while (s.tick < max_ticks && s.levels_cleared < levels && s.phase != sim::Phase::game_over) {
      sim::TickInputs in;
      if (s.tick == 0) {
        for (std::int64_t p = 1; p <= players; ++p)
          in.joins.push_back({static_cast<sim::PlayerId>(p), "bot" + std::to_string(p)});
      }
      for (const auto& p : s.players) in.players.push_back(sim::bot_tick(s, p.id));
      run_tick(in);
    }
  }

  nlohmann::json report = {
      {"mode", "match"},
      {"seed", seed},
      {"model", sim::to_string(cfg.model)},
      {"tick_rate_hz", cfg.tick_rate_hz},
      {"replay", inputs_path.has_value()},
      {"hashes_checked", hashes_checked},
      {"phase", sim::to_string(s.phase)},
      {"level", s.level},
      {"levels_cleared", s.levels_cleared},
      {"ticks", s.tick},
      {"seconds", static_cast<double>(s.tick) / cfg.tick_rate_hz},
      {"level_clear_ticks", tally.level_clear_ticks},
      {"level_restarts", tally.restarts},
      {"falls", tally.falls},
      {"enemies_defeated", tally.defeats},
      {"enemies_fell_untouched", tally.untouched},
      {"purchase_refusals", tally.refusals},
  };
  auto& per = report["players"] = nlohmann::json::array();
  for (const auto& p : s.players) {
    per.push_back({{"id", p.id},
                   {"name", p.name},
                   {"coins", p.eco.coins},
                   {"lives", p.eco.lives},
                   {"purchases", p.eco.purchases},
                   {"defeats", p.eco.defeats},
                   {"mass", p.eco.mass},
                   {"vmax_u_per_s", p.eco.vmax_u_per_s},
                   {"accel_u_per_s2", p.eco.accel_u_per_s2},
                   {"multiplier", p.eco.multiplier},
                   {"bank", p.eco.bank},
                   {"rockets", p.eco.rockets}});
  }
  report["state_hash"] = room::hex16(sim::match_hash(s));
  std::cout << report.dump() << "\n";
  return 0;
}

}  // namespace fts::simtool
