// fts-client --replay: a server record (fts-server --record) played back in the terminal.
// The client runs common/'s deterministic match on the record's seed and inputs, the same
// code the server ran, so what it shows is exact; the record's hash lines are checked on
// the way. This is the one place the client simulates. Pure: time and keys are passed in.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <istream>
#include <map>
#include <utility>
#include <string>
#include <variant>
#include <vector>

#include "fts/protocol/snapshot.hpp"
#include "fts/room/record.hpp"
#include "fts/room/stepper.hpp"
#include "fts/sim/match.hpp"
#include "ui/view.hpp"

namespace fts::client {

// The history's reader is fts_room's, as the server's (a journal or a record, one reader).
using room::load_history;
using room::load_tape;
using room::Tape;

// Playback speeds (x), from a table: - and + step through it.
inline constexpr std::array<double, 5> kReplaySpeeds = {0.5, 1, 2, 4, 8};

class Replay {
 public:
  explicit Replay(Tape tape);

  // Steps the match up to `tick` (never back; at most to the record's end).
  void run_to(std::int64_t tick);
  // To the start of level `level` (from the beginning when it lies behind), or to the
  // end of the record when the match never reaches it.
  void seek_level(std::int64_t level);
  // Plays `elapsed_ms` of wall time at the current speed unless paused.
  void advance(std::uint64_t elapsed_ms);

  void toggle_pause() { paused_ = !paused_; }
  void faster() { speed_ = std::min<std::size_t>(speed_ + 1, kReplaySpeeds.size() - 1); }
  void slower() { speed_ = speed_ > 0 ? speed_ - 1 : 0; }
  double speed() const { return kReplaySpeeds[speed_]; }
  bool paused() const { return paused_; }
  bool at_end() const { return state().tick >= tape_.last_tick; }

  const sim::MatchState& state() const { return room_.match(); }
  const Tape& tape() const { return tape_; }
  // What a client would have been sent now, with the recent events.
  protocol::Snapshot snapshot() const;
  // Events since the last call (for the message log and the scoreboard), oldest first.
  std::vector<protocol::Event> take_events();
  // True once after each seek: the log starts again from the new position.
  bool take_seeked() { return std::exchange(seeked_, false); }
  // The score book up to the position (every event since the match's start tallied).
  const std::map<std::uint32_t, Score>& scores() const { return scores_; }
  // The last kLogKeep events up to the position, oldest first (the log after a seek).
  const std::deque<protocol::Event>& recent() const { return recent_; }
  // "" or the first hash that differed ("tick 300: recorded ..., replayed ...").
  const std::string& mismatch() const { return mismatch_; }

 private:
  void restart();
  void step_once();

  Tape tape_;
  room::RoomStepper room_;  // the server rooms' stepper: the same events window
  std::size_t next_line_ = 0;
  std::size_t next_hash_ = 0;
  std::size_t speed_ = 1;  // x1
  bool paused_ = false;
  double carry_ticks_ = 0;
  std::vector<protocol::Event> fresh_;
  std::deque<protocol::Event> recent_;
  std::map<std::uint32_t, Score> scores_;
  bool seeked_ = false;
  std::string mismatch_;
};

// The replay's events into the view, each frame: the log and the score book follow the
// position; after a seek the log is the position's latest lines, not the old ones
// (issue 37: after `9` the log said "Level 1 started.").
void replay_log(Replay& r, const protocol::Snapshot& snap, ViewState& view, std::uint64_t now_ms);

// The footer of the replay screen: position, speed and the keys.
std::string replay_footer(const Replay& r, int cols);

}  // namespace fts::client
