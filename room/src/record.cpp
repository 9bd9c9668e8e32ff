#include "fts/room/record.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "fts/room/json_fields.hpp"
#include "fts/room/match_config_json.hpp"
#include "fts/room/stepper.hpp"
#include "fts/room/text.hpp"

namespace fts::room {

namespace {
// A history's ticks come in order and close together (a hash line every 10 or 100
// ticks): a jump beyond this is a damaged file, not hours of empty ticks to simulate.
constexpr std::int64_t kMaxGapTicks = 10'000'000;
}  // namespace

bool empty_inputs(const sim::TickInputs& in) {
  return in.joins.empty() && in.leaves.empty() && in.away.empty() && in.back.empty() && in.quit.empty() &&
         in.players.empty();
}

RecordWriter::RecordWriter(std::ostream& out, std::uint64_t seed, const sim::MatchConfig& cfg,
                           const std::string& version)
    : out_(out) {
  nlohmann::ordered_json head;
  head["fts_record"] = kRecordFormat;
  head["version"] = version;
  head["seed"] = seed;
  head["config"] = match_config_to_json(cfg);
  out_ << head.dump() << "\n";
}

void RecordWriter::inputs(std::int64_t tick, const sim::TickInputs& in) {
  if (empty_inputs(in)) return;
  out_ << to_input_line(tick, in) << "\n";
}

void RecordWriter::stepped(const sim::MatchState& state) {
  if (state.tick % kRecordHashEvery != 0) return;
  hash_line(state);
}

void RecordWriter::hash_line(const sim::MatchState& state) {
  out_ << R"({"tick":)" << state.tick << R"(,"hash":")" << hex16(sim::match_hash(state)) << "\"}\n";
}

std::variant<Tape, std::string> load_tape(std::istream& in, std::size_t max_lines) {
  std::string line;
  if (!std::getline(in, line)) return std::string("the record is empty");
  std::string why;
  auto head = parse_json(line, why);
  if (!head) return "line 1: not a record header: " + why;
  if (!head->is_object() || !head->contains("fts_record") || !head->contains("seed") || !head->contains("config"))
    return std::string("line 1: not a record header (needs fts_record, seed, config)");
  if (!(*head)["fts_record"].is_number_integer() || (*head)["fts_record"].get<std::int64_t>() != kRecordFormat)
    return "line 1: a record of format " + (*head)["fts_record"].dump() + " (written by version " +
           head->value("version", std::string("?")) + "); this build reads format " + std::to_string(kRecordFormat);
  if (!(*head)["seed"].is_number_unsigned()) return std::string("line 1: seed must be a non-negative integer");
  auto cfg = parse_match_config((*head)["config"].dump());
  if (auto* err = std::get_if<std::string>(&cfg)) return "line 1: config: " + *err;
  Tape t;
  t.format = "record " + std::to_string(kRecordFormat);
  t.seed = (*head)["seed"].get<std::uint64_t>();
  t.config = std::get<sim::MatchConfig>(cfg);
  for (std::size_t no = 2; std::getline(in, line); ++no) {
    if (line.empty()) continue;
    if (no > max_lines) return "the record has more than " + std::to_string(max_lines) + " lines";
    const std::string where = "line " + std::to_string(no) + ": ";
    // Each line is parsed once and dispatched on its keys: a hash line is the object
    // {"tick","hash"}; anything else must be an input line. (Searching the text for
    // "hash" took a player named hash for a hash line.)
    auto j = parse_json(line, why);
    if (!j) return where + "invalid JSON: " + why;
    if (j->is_object() && j->contains("hash") &&
        (j->size() != 2 || !j->contains("tick") || !(*j)["tick"].is_number_integer() || !(*j)["hash"].is_string()))
      return where + "a hash line needs an integer tick and a string hash, and nothing else";
    if (auto err = append_line(t, *j, no, ""); !err.empty()) return where + err;
  }
  return t;
}

std::string append_line(Tape& t, const nlohmann::json& j, std::size_t line, const std::string& file) {
  std::int64_t tick = 0;
  const bool hash = j.is_object() && j.contains("hash");
  InputLine il;
  if (hash) {
    tick = j.at("tick").get<std::int64_t>();
  } else {
    auto parsed = input_line_from_json(j);
    if (auto* err = std::get_if<std::string>(&parsed)) return *err;
    il = std::move(std::get<InputLine>(parsed));
    tick = il.tick;
  }
  if (tick < t.last_tick) return "tick " + std::to_string(tick) + " goes back in time";
  if (tick - t.last_tick > kMaxGapTicks)
    return "tick " + std::to_string(tick) + " is too far ahead of " + std::to_string(t.last_tick);
  if (hash) t.hashes.push_back({tick, j.at("hash").get<std::string>(), line, file});
  else t.lines.push_back({il.tick, std::move(il.inputs)});
  t.last_tick = std::max(t.last_tick, tick + (hash ? 0 : 1));
  return {};
}

std::variant<ReplayReport, std::string> replay_record(std::istream& in) {
  auto loaded = load_tape(in);
  if (auto* err = std::get_if<std::string>(&loaded)) return *err;
  return replay_tape(std::get<Tape>(loaded));
}

std::variant<ReplayReport, std::string> replay_tape(const Tape& tape) {
  RoomStepper room(tape.config, tape.seed);
  ReplayReport r;
  r.format = tape.format;
  std::size_t next_line = 0;
  for (const TapeHash& h : tape.hashes) {
    while (room.match().tick < h.tick) {
      const bool due = next_line < tape.lines.size() && tape.lines[next_line].tick == room.match().tick;
      room.step(due ? tape.lines[next_line++].inputs : sim::TickInputs{});
    }
    const std::string got = hex16(sim::match_hash(room.match()));
    if (got != h.hex)
      return (h.file.empty() ? "" : h.file + " ") + "line " + std::to_string(h.line) + ": hash mismatch at tick " + std::to_string(h.tick) + ": recorded " +
             h.hex + ", replayed " + got;
    ++r.hashes_checked;
  }
  while (room.match().tick < tape.last_tick) {
    const bool due = next_line < tape.lines.size() && tape.lines[next_line].tick == room.match().tick;
    room.step(due ? tape.lines[next_line++].inputs : sim::TickInputs{});
  }
  r.ticks = room.match().tick;
  r.final_hash = sim::match_hash(room.match());
  r.state = room.match();
  return r;
}

}  // namespace fts::room
