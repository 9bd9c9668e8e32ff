// The match record: a header line, then the input of every non-empty tick and the state
// hash every 100 ticks, one JSON object per line. A seed plus this log reproduces the
// match bit for bit; replay_record re-runs it and checks every hash.
//
//   {"fts_record":1,"version":"0.1.0","seed":7,"config":{...MatchConfig...}}
//   {"tick":0,"joins":[{"player":1,"name":"ann"}]}
//   {"tick":12,"players":[{"id":1,"x":1}]}
//   {"tick":100,"hash":"9c3e..."}            <- match_hash after 100 ticks were stepped
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <variant>

#include "fts/sim/match.hpp"

namespace fts::host {

constexpr std::int64_t kRecordHashEvery = 100;

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

struct ReplayReport {
  std::int64_t ticks = 0;
  std::int64_t hashes_checked = 0;
  std::uint64_t final_hash = 0;
  sim::MatchState state;  // at the end
};

// Either the report (every hash equal) or a message naming the line and what differed.
std::variant<ReplayReport, std::string> replay_record(std::istream& in);

}  // namespace fts::host
