// A match's history: its seed, its config, the input of every non-empty tick and state
// hashes to check; a seed plus this log reproduces the match bit for bit. Two formats on
// disk, one reader (load_history: fts-server --replay checks it, fts-sim --inputs goes on
// from it, fts-client --replay plays it), which says which format it read:
//   a journal (server/store/journal.hpp): a directory of segments, each a header and a
//     checkpoint, then input, hash (every 10 ticks) and session lines; one that keeps
//     every segment from the first is a whole history;
//   the record of format 1 (one file, below), which servers wrote before issue 38.
// The one writer is the journal's (server/store/journal.hpp, a record keeps every segment);
// RecordWriter writes format 1 only so that tests can make such files.
//
//   {"fts_record":1,"version":"0.1.0","seed":7,"config":{...MatchConfig...}}
//   {"tick":0,"joins":[{"player":1,"name":"ann"}]}
//   {"tick":12,"players":[{"id":1,"x":1}]}
//   {"tick":100,"hash":"9c3e..."}            <- match_hash after 100 ticks were stepped
#pragma once

#include <cstdint>
#include <filesystem>
#include <istream>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fts/sim/match.hpp"

namespace fts::room {

constexpr std::int64_t kRecordHashEvery = 100;
// The record format this build writes and reads ("fts_record" in the header).
constexpr std::int64_t kRecordFormat = 1;
// The journal format this build writes and reads ("fts_journal" in a segment's header).
inline constexpr int kJournalFormat = 1;

// The file name of journal segment n ("journal-000001.jsonl") and the segments in a
// journal's directory, oldest first.
std::string segment_name(std::uint64_t n);
std::vector<std::pair<std::uint64_t, std::filesystem::path>> list_segments(const std::filesystem::path& dir);

// Nothing happens in the tick: no line is written for it.
bool empty_inputs(const sim::TickInputs& in);

class RecordWriter {
 public:
  RecordWriter(std::ostream& out, std::uint64_t seed, const sim::MatchConfig& cfg, const std::string& version);
  // Call before stepping tick `tick` (== state.tick) with the inputs given to step().
  void inputs(std::int64_t tick, const sim::TickInputs& inputs);
  // Call after stepping; writes the hash when state.tick is a multiple of kRecordHashEvery.
  void stepped(const sim::MatchState& state);
  // The hash line of the state now, whatever its tick (a room that closes ends its
  // record with it, so a replay ends on the hash the room ended on).
  void hash_line(const sim::MatchState& state);
  void flush() { out_.flush(); }

 private:
  std::ostream& out_;
};

// A record read whole.
struct TapeLine {
  std::int64_t tick = 0;
  sim::TickInputs inputs;
};
struct TapeHash {
  std::int64_t tick = 0;
  std::string hex;        // match_hash after `tick` ticks, as recorded
  std::size_t line = 0;   // its line in the record (1-based), for the error
  std::string file;       // its journal segment's file name ("" in a record)
};
struct Tape {
  std::string format;  // what was read: "record 1" or "journal 1"
  std::uint64_t seed = 0;
  sim::MatchConfig config;
  std::vector<TapeLine> lines;  // in tick order
  std::vector<TapeHash> hashes;  // to check, in tick order
  std::int64_t last_tick = 0;   // the last tick the record names
};

// Reads a whole record; an error names the line (and a record of another format its
// format). Bounded: at most max_lines lines.
std::variant<Tape, std::string> load_tape(std::istream& in, std::size_t max_lines = 5'000'000);
// Adds one line of a history to the tape, in tick order: a line with "hash" (its tick and
// hash) or an input line. "" or why not (the caller names the line).
std::string append_line(Tape& t, const nlohmann::json& j, std::size_t line, const std::string& file);
// Reads a history: a journal directory (every segment from the first; a torn last line,
// a crash's, ends it) or a record file. An error names the file and line.
std::variant<Tape, std::string> load_history(const std::filesystem::path& path, std::size_t max_lines = 5'000'000);

struct ReplayReport {
  std::string format;  // the history's (Tape::format)
  std::int64_t ticks = 0;
  std::int64_t hashes_checked = 0;
  std::uint64_t final_hash = 0;
  sim::MatchState state;  // at the end
};

// Steps the record through the room stepper: either the report (every hash equal) or a
// message naming the line and what differed.
std::variant<ReplayReport, std::string> replay_record(std::istream& in);
std::variant<ReplayReport, std::string> replay_tape(const Tape& tape);
std::variant<ReplayReport, std::string> replay_history(const std::filesystem::path& path);

}  // namespace fts::room
