#include "sim/match_cli.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "fts/cli/option_table.hpp"
#include "fts/sim/bot_player.hpp"
#include "fts/sim/match.hpp"
#include "fts/room/match_config_json.hpp"
#include "fts/room/record.hpp"
#include "fts/room/text.hpp"

namespace fts::simtool {
namespace {

// fts-sim --match's options (defaults: the initialisers) and their table.
struct MatchOptions {
  std::int64_t players = 1, levels = 5, max_ticks = 1'000'000, seed = 1;
  std::optional<std::string> model;
  std::optional<std::int64_t> tick_rate;
  std::optional<std::string> config, inputs, record;
  bool events = false;
};

using cli::Int, cli::Maybe, cli::Text;
constexpr std::int64_t kMax = INT64_MAX;
inline constexpr auto kMatchTable = std::tuple{
    cli::value("--players", "", &MatchOptions::players, Int<std::int64_t>{1, 64}, "must be 1..64",
               "bots that play (at most the config's max_players)", "N"),
    cli::value("--levels", "", &MatchOptions::levels, Int<std::int64_t>{0, 1'000'000}, "must be 0..1000000",
               "stop after this many levels cleared", "N"),
    cli::value("--max-ticks", "", &MatchOptions::max_ticks, Int<std::int64_t>{0, 1'000'000'000'000}, "must be >= 0",
               "stop after this many ticks", "T"),
    cli::value("--seed", "", &MatchOptions::seed, Int<std::int64_t>{0, kMax}, "must be >= 0",
               "seed of the match's random generator", "S"),
    cli::value("--model", "", &MatchOptions::model, Maybe<cli::OneOf>{{{"seed", "discrete", "continuous"}}},
               "must be seed, discrete or continuous", "physics model (default: the config's)", "seed|discrete|continuous"),
    cli::value("--tick-rate", "", &MatchOptions::tick_rate, Maybe<Int<std::int64_t>>{{1, 10000}},
               "must be 1..10000 (integer Hz)", "ticks per second (default: the config's)", "HZ"),
    cli::value("--config", "", &MatchOptions::config, Maybe<Text>{}, "needs a file",
               "match configuration JSON (docker/server-config.example.json)", "FILE"),
    cli::value("--inputs", "", &MatchOptions::inputs, Maybe<Text>{}, "needs a file",
               "replay: an input log, a record file or a journal directory (its own seed and config, every hash "
               "checked) instead of the bots",
               "FILE"),
    cli::value("--record", "", &MatchOptions::record, Maybe<Text>{}, "needs a file",
               "write the match's inputs to FILE (one line a tick, for --inputs)", "FILE"),
    cli::on("--events", "", &MatchOptions::events, "print every event as a JSON line on stderr"),
};
static_assert(fields::names_every_member<MatchOptions>(kMatchTable), "a member of MatchOptions has no row");

constexpr cli::Program kMatchProgram{
    "fts-sim",
    "usage: fts-sim --match [options]\n",
    "Plays a headless match with built-in bots (or replays --inputs) and prints one JSON report.\n",
    cli::Wording{false, ""},
    false,
    false,
};

const std::vector<cli::RowInfo>& match_rows() {
  static const std::vector<cli::RowInfo> r = cli::infos(kMatchTable);
  return r;
}

int usage(const std::string& msg) {
  std::cerr << "fts-sim --match: " << msg << "\n" << match_help();
  return 2;
}

nlohmann::json event_json(std::int64_t tick, const sim::Event& event) {
  nlohmann::json j = {{"tick", tick}, {"event", sim::to_string(sim::kind_of(event))}};
  auto player = [&](sim::PlayerId id) {
    if (id) j["player"] = id;
  };
  std::visit(sim::Overloaded{
                 [&](const sim::Joined& e) { player(e.player); j["name"] = e.name; },
                 [&](const sim::JoinRefused& e) { player(e.player); j["reason"] = sim::to_string(e.reason); },
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

std::string match_help() { return cli::help_text(kMatchProgram, match_rows()); }
std::string match_markdown() { return cli::markdown(kMatchProgram, match_rows(), "fts-sim --match"); }

int run_match_cli(const std::vector<std::string>& args) {
  MatchOptions o;
  auto parsed = cli::parse(kMatchProgram, kMatchTable, o, args);
  if (const auto* e = std::get_if<cli::Error>(&parsed)) return usage(e->message);
  std::int64_t players = o.players, levels = o.levels, max_ticks = o.max_ticks, seed = o.seed;
  const bool print_events = o.events;
  const auto &model = o.model, &config_path = o.config, &inputs_path = o.inputs, &record_path = o.record;
  const auto& tick_rate = o.tick_rate;

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
  if (tick_rate) cfg.tick_rate_hz = static_cast<double>(*tick_rate);
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
