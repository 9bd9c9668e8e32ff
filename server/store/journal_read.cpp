// The journal's reader (store/journal.hpp): a room rebuilt from its newest usable
// segment, the damage said, never a crash.
#include <fstream>

#include <nlohmann/json.hpp>

#include "store/journal.hpp"
#include "fts/room/json_fields.hpp"
#include "fts/room/match_config_json.hpp"
#include "store/match_state_json.hpp"
#include "fts/room/stepper.hpp"
#include "fts/room/text.hpp"

namespace fts::store {

// The JSON helpers and text conversions of the record format live in fts_room.
using namespace fts::room;
namespace {

using nlohmann::json;

JournalSession session_from(const json& j) {
  JournalSession s;
  s.player = j.at("player").get<std::uint32_t>();
  s.name = j.at("name").get<std::string>();
  s.verifier = j.at("verifier").get<std::string>();
  s.quit = j.at("quit").get<bool>();
  if (j.contains("identity")) s.identity = j.at("identity").get<std::string>();  // journals before issue 41 lack both
  if (j.contains("career")) s.career = j.at("career").get<std::string>();
  return s;
}

// The match being rebuilt goes through the room stepper, as the crashed server's room
// did: the same step, the same event numbering (so the resumed event_seq equals the
// crashed server's, checked at every hash line).
struct Replay {
  room::RoomStepper stepper;
  std::map<std::uint32_t, JournalSession> sessions;
  const sim::MatchState& state() const { return stepper.match(); }
};

struct SegmentStart {
  ResumedRoom room;
  Replay now;
};

// Header and checkpoint of one segment, or why they are not usable.
std::variant<SegmentStart, std::string> open_segment_file(std::istream& in) {
  std::string line, why;
  if (!std::getline(in, line) || in.eof()) return std::string("line 1: no complete header");
  auto head = parse_json(line, why);
  if (!head) return "line 1: invalid JSON: " + why;
  SegmentStart s;
  try {
    if (head->at("fts_journal").get<int>() != kJournalFormat) return std::string("line 1: unknown journal format");
    s.room.room = head->at("room").get<std::string>();
    s.room.room_id = head->value("room_id", std::uint32_t{0});
    s.room.is_private = head->value("private", false);
    s.room.version = head->at("version").get<std::string>();
    s.room.seed = head->at("seed").get<std::uint64_t>();
    s.room.segment = head->at("segment").get<std::uint64_t>();
    auto cfg = parse_match_config(head->at("config").dump());
    if (auto* err = std::get_if<std::string>(&cfg)) return "line 1: config: " + *err;
    s.room.config = std::get<sim::MatchConfig>(cfg);
  } catch (const std::exception& e) {
    return std::string("line 1: ") + e.what();
  }
  if (!std::getline(in, line) || in.eof()) return std::string("line 2: no complete checkpoint");
  auto cp = parse_json(line, why);
  if (!cp) return "line 2: invalid JSON: " + why;
  try {
    auto state = match_state_from_json(cp->at("checkpoint"), sim::make_match(s.room.config, s.room.seed));
    if (auto* err = std::get_if<std::string>(&state)) return "line 2: " + *err;
    auto& read = std::get<sim::MatchState>(state);
    const std::string want = cp->at("hash").get<std::string>();
    const std::string got = hex16(sim::match_hash(read));
    if (want != got) return "line 2: checkpoint hash " + want + ", read back " + got;
    if (cp->at("tick").get<std::int64_t>() != read.tick) return std::string("line 2: tick differs from the state's");
    s.now.stepper = room::RoomStepper(std::move(read), cp->at("event_seq").get<std::uint32_t>());
    for (const json& js : cp->at("sessions")) {
      JournalSession js2 = session_from(js);
      s.now.sessions[js2.player] = std::move(js2);
    }
  } catch (const std::exception& e) {
    return std::string("line 2: ") + e.what();
  }
  s.room.checkpoint_tick = s.now.state().tick;
  return s;
}

// A replay's gaps are the journal's empty ticks; more than this is a damaged file.
constexpr std::int64_t kMaxGapTicks = 10'000'000;

// Replays the lines after the checkpoint into `r`; returns "" or the damage.
std::string replay_lines(std::istream& in, Replay& now, ResumedRoom& r) {
  Replay good = now;  // the state at the last hash that matched (or the checkpoint)
  auto step_one = [&](const sim::TickInputs& inputs) {
    now.stepper.step(inputs);
    ++r.ticks_replayed;
  };
  auto reach = [&](std::int64_t tick, const std::string& where) -> std::string {
    if (tick < now.state().tick) return where + "tick " + std::to_string(tick) + " goes back in time";
    if (tick - now.state().tick > kMaxGapTicks) return where + "tick " + std::to_string(tick) + " is too far ahead";
    while (now.state().tick < tick) step_one({});
    return {};
  };
  std::string line, why;
  for (std::int64_t no = 3; std::getline(in, line); ++no) {
    const std::string where = "line " + std::to_string(no) + ": ";
    if (in.eof()) return where + "torn (no end of line); resumed before it";
    auto parsed = parse_json(line, why);
    if (!parsed) return where + "invalid JSON (" + why + "); resumed before it";
    const json& j = *parsed;
    try {
      if (j.contains("hash")) {
        const std::int64_t tick = j.at("tick").get<std::int64_t>();
        if (auto err = reach(tick, where); !err.empty()) return err;
        const std::string got = hex16(sim::match_hash(now.state()));
        const std::string want = j.at("hash").get<std::string>();
        const auto seq = j.at("event_seq").get<std::uint32_t>();
        if (got != want || seq != now.stepper.event_seq()) {
          const std::string damage = where + "hash mismatch at tick " + std::to_string(tick) + " (journal " + want +
                                     ", replay " + got + "; events " + std::to_string(seq) + ", replay " +
                                     std::to_string(now.stepper.event_seq()) + "); resumed at tick " +
                                     std::to_string(good.state().tick);
          now = std::move(good);
          return damage;
        }
        ++r.hashes_checked;
        good = now;
      } else if (j.contains("session")) {
        JournalSession s = session_from(j.at("session"));
        now.sessions[s.player] = std::move(s);
      } else if (j.contains("released")) {
        now.sessions.erase(j.at("released").get<std::uint32_t>());
      } else {
        auto il = input_line_from_json(j);
        if (auto* err = std::get_if<std::string>(&il)) return where + *err + "; resumed before it";
        const auto& input = std::get<InputLine>(il);
        if (auto err = reach(input.tick, where); !err.empty()) return err;
        step_one(input.inputs);
      }
    } catch (const std::exception& e) {
      return where + e.what() + "; resumed before it";
    }
  }
  return {};
}

}  // namespace

std::variant<ResumedRoom, std::string> read_journal(const std::filesystem::path& room_dir) {
  const auto segments = list_segments(room_dir);
  if (segments.empty()) return "no journal segments in " + room_dir.string();
  std::vector<std::string> skipped;
  for (auto it = segments.rbegin(); it != segments.rend(); ++it) {
    std::ifstream in(it->second);
    const std::string name = it->second.filename().string();
    if (!in) {
      skipped.push_back(name + ": cannot read");
      continue;
    }
    auto start = open_segment_file(in);
    if (auto* err = std::get_if<std::string>(&start)) {
      skipped.push_back(name + ": " + *err);
      continue;
    }
    auto& s = std::get<SegmentStart>(start);
    ResumedRoom r = std::move(s.room);
    Replay now = std::move(s.now);
    r.damage = replay_lines(in, now, r);
    if (!r.damage.empty()) r.damage = name + ": " + r.damage;
    r.state = now.stepper.match();
    r.event_seq = now.stepper.event_seq();
    for (auto& [id, js] : now.sessions) r.sessions.push_back(std::move(js));
    r.skipped = std::move(skipped);
    return r;
  }
  std::string why = "no usable journal segment in " + room_dir.string() + ":";
  for (const auto& s : skipped) why += " [" + s + "]";
  return why;
}

}  // namespace fts::store
