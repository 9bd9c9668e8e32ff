#include "host/record.hpp"


#include <nlohmann/json.hpp>

#include "host/json_fields.hpp"
#include "host/match_config_json.hpp"
#include "host/text.hpp"

namespace fts::host {


RecordWriter::RecordWriter(std::ostream& out, std::uint64_t seed, const sim::MatchConfig& cfg,
                           const std::string& version)
    : out_(out) {
  nlohmann::ordered_json head;
  head["fts_record"] = 1;
  head["version"] = version;
  head["seed"] = seed;
  head["config"] = match_config_to_json(cfg);
  out_ << head.dump() << "\n";
}

void RecordWriter::inputs(std::int64_t tick, const sim::TickInputs& in) {
  if (in.joins.empty() && in.leaves.empty() && in.away.empty() && in.back.empty() && in.quit.empty() &&
      in.players.empty())
    return;
  out_ << to_input_line(tick, in) << "\n";
}

void RecordWriter::stepped(const sim::MatchState& state) {
  if (state.tick % kRecordHashEvery != 0) return;
  hash_line(state);
}

void RecordWriter::hash_line(const sim::MatchState& state) {
  out_ << R"({"tick":)" << state.tick << R"(,"hash":")" << hex16(sim::match_hash(state)) << "\"}\n";
}

std::variant<ReplayReport, std::string> replay_record(std::istream& in) {
  std::string line;
  if (!std::getline(in, line)) return std::string("empty record");
  std::string why;
  auto parsed_head = parse_json(line, why);
  if (!parsed_head) return "line 1: not a record header: " + why;
  nlohmann::json& head = *parsed_head;
  if (!head.is_object() || !head.contains("fts_record") || !head.contains("seed") || !head.contains("config"))
    return std::string("line 1: not a record header (needs fts_record, seed, config)");
  if (!head["seed"].is_number_unsigned()) return std::string("line 1: seed must be a non-negative integer");
  auto cfg = parse_match_config(head["config"].dump());
  if (auto* err = std::get_if<std::string>(&cfg)) return "line 1: config: " + *err;

  ReplayReport r;
  r.state = sim::make_match(std::get<sim::MatchConfig>(cfg), head["seed"].get<std::uint64_t>());
  // A record's ticks come in order and close together (a hash line every 100 ticks):
  // a jump beyond this is a damaged file, not hours of empty ticks to simulate.
  constexpr std::int64_t kMaxGapTicks = 10'000'000;
  auto step_until = [&](std::int64_t tick) {
    while (r.state.tick < tick) sim::step(r.state, {});
  };
  auto too_far = [&](std::int64_t tick) { return tick - r.state.tick > kMaxGapTicks; };
  for (std::int64_t no = 2; std::getline(in, line); ++no) {
    if (line.empty()) continue;
    const std::string where = "line " + std::to_string(no) + ": ";
    // Each line is parsed once and dispatched on its keys: a hash line is the object
    // {"tick","hash"}; anything else must be an input line. (Searching the text for
    // "hash" took a player named hash for a hash line.)
    auto json_line = parse_json(line, why);
    if (!json_line) return where + "invalid JSON: " + why;
    const nlohmann::json& j = *json_line;
    if (j.is_object() && j.contains("hash")) {
      if (j.size() != 2 || !j.contains("tick") || !j["tick"].is_number_integer() || !j["hash"].is_string())
        return where + "a hash line needs an integer tick and a string hash, and nothing else";
      const std::int64_t tick = j["tick"].get<std::int64_t>();
      if (tick < r.state.tick) return where + "tick " + std::to_string(tick) + " goes back in time";
      if (too_far(tick)) return where + "tick " + std::to_string(tick) + " is too far ahead of " + std::to_string(r.state.tick);
      step_until(tick);
      const std::string got = hex16(sim::match_hash(r.state));
      if (got != j["hash"].get<std::string>())
        return where + "hash mismatch at tick " + std::to_string(tick) + ": recorded " +
               j["hash"].get<std::string>() + ", replayed " + got;
      ++r.hashes_checked;
      continue;
    }
    auto parsed = input_line_from_json(j);
    if (auto* err = std::get_if<std::string>(&parsed)) return where + *err;
    const auto& il = std::get<InputLine>(parsed);
    if (il.tick < r.state.tick) return where + "tick " + std::to_string(il.tick) + " goes back in time";
    if (too_far(il.tick)) return where + "tick " + std::to_string(il.tick) + " is too far ahead of " + std::to_string(r.state.tick);
    step_until(il.tick);
    sim::step(r.state, il.inputs);
  }
  r.ticks = r.state.tick;
  r.final_hash = sim::match_hash(r.state);
  return r;
}

}  // namespace fts::host
