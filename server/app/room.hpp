// One room: a match of its own (seed, inputs, events, record, snapshots). The process
// part (game_host) owns the endpoint and hands each room the connection events, inputs
// and commands of its own sessions; a room never sees another room's players.
#pragma once

#include <algorithm>
#include <deque>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "app/careers.hpp"
#include "app/log.hpp"
#include "app/options.hpp"
#include "app/stats.hpp"
#include "fts/protocol/server.hpp"
#include "fts/sim/match.hpp"
#include "store/journal.hpp"
#include "fts/room/record.hpp"
#include "fts/room/stepper.hpp"
#include "profiles/writer.hpp"

namespace fts::server {

// A frame may name a tick at most kMaxLeadMs ahead of the room's (beyond it is no honest
// client's lead: applied at once), counted in the room's ticks: 100 at 100 Hz, 20 at
// 20 Hz (a fixed 100 ticks was 5 s at 20 Hz). A player's early frames wait in a buffer
// of at most kMaxEarlyFrames.
inline constexpr std::int64_t kMaxLeadMs = 1000;
inline constexpr std::size_t kMaxEarlyFrames = 32;
inline std::int64_t max_lead_ticks(double tick_rate_hz) {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(tick_rate_hz * static_cast<double>(kMaxLeadMs) / 1000.0));
}

// Input frames by when they arrived against the tick they were meant for.
struct InputTiming {
  std::uint64_t on_time = 0;  // arrived early and applied at their tick
  std::uint64_t late = 0;     // arrived after their tick: applied at once
  std::uint64_t untimed = 0;  // no tick (0): applied at once
  std::uint64_t too_early = 0;  // meant for more than max_lead_ticks ahead: applied at once
  std::uint64_t overflow = 0;   // the early buffer was full: its oldest applied at once
  InputTiming& operator+=(const InputTiming& o) {
    on_time += o.on_time, late += o.late, untimed += o.untimed, too_early += o.too_early, overflow += o.overflow;
    return *this;
  }
};

class Room {
 public:
  Room(std::uint32_t id, std::string code, bool is_private, std::uint64_t seed, const Options& options,
       const sim::MatchConfig& config);

  // Records the match from now on into the directory `dir`: a journal that keeps every
  // segment (store/journal.hpp), written by its own thread, never by the tick; segments
  // of an earlier record there are removed first. False: the directory cannot be used.
  bool record_to(const std::string& dir, const std::string& version);
  // The room closes: the record's last hash line (the state it ends on), then its writer,
  // finishing on its own thread (nullptr without a record).
  std::unique_ptr<store::JournalWriter> finish_record();

  // What the endpoint reported for this room's sessions since the last tick.
  void on_event(const protocol::ServerEvent& e, const protocol::ServerEndpoint& endpoint);
  void on_input(const protocol::PlayerInput& pi, std::uint64_t now_ms);
  void on_command(const protocol::PlayerCommand& pc, protocol::ServerEndpoint& endpoint, std::uint64_t now_ms);
  // A tick in three parts, so that rooms step on several threads (issue 29): step()
  // touches only this room (its match, record and journal queue) and may run on any
  // thread while other rooms step; publish() answers the step's commands, logs its
  // events and tells the endpoint the tick, on the thread that owns the endpoint, in
  // room order; send_snapshots() marks who of `members` (its connected sessions, handed
  // over by the endpoint: protocol/server_jobs.hpp) watches, out of lives, and seals this
  // room's snapshot for them into `lane`; it may run beside other rooms' again: it is
  // given no endpoint.
  void step(std::uint64_t now_ms);
  void publish(protocol::ServerEndpoint& endpoint, std::uint64_t now_ms);
  void send_snapshots(const protocol::RoomSessions& members, std::uint64_t now_ms, protocol::SendLane& lane);
  void flush();
  // Ends the record with the hash of the state now (the room closes).
  void seal();

  // ---- crash-safe journal (issue 15). Resumes the match and the event numbering from a
  // journal (the host restores the sessions); journals this room from now on.
  void resume_from(const store::ResumedRoom& room);
  void journal_to(store::JournalConfig config, const protocol::ServerEndpoint& endpoint);
  // The room closes: its journal finishes (JournalWriter::finish) and is handed over.
  std::unique_ptr<store::JournalWriter> finish_journal();
  const store::JournalWriter* journal() const { return journal_.get(); }
  store::JournalWriter* journal() { return journal_.get(); }
  // The journal as last seen (once a second): failing (an I/O error), times it failed, why.
  bool journal_failing() const { return journal_failing_; }
  std::uint64_t journal_failures() const { return journal_failures_; }
  const std::string& journal_error() const { return journal_error_; }
  // ---- profiles (issue 41): players with an identity are followed (app/careers.hpp); a
  // result goes to `writer` (which never waits) when the player's match ends; `unix_s`
  // is the wall clock (tests set their own). Without a writer nothing is followed.
  void use_profiles(profiles::Writer* writer, std::function<std::int64_t()> unix_s) {
    profiles_ = writer;
    unix_s_ = std::move(unix_s);
  }
  void restore_career(const store::JournalSession& s) { careers_.restore(s.player, s.identity, s.career); }
  // The room closes: its players' running results (closed).
  void close_careers();
  // An identity asked to be forgotten: its players here are followed no more.
  void forget_identity(const std::string& identity) { careers_.forget(identity); }
  const Careers& careers() const { return careers_; }
  // Purchases counted for the fleet's metrics (Stats::Totals), when set.
  void count_into(Stats::Totals* totals) { totals_ = totals; }

  std::uint32_t id() const { return id_; }
  const std::string& code() const { return code_; }
  bool is_private() const { return private_; }
  std::uint64_t seed() const { return seed_; }
  const sim::MatchState& match() const { return stepper_.match(); }
  // The name the match gave a player, the one every screen shows (a second "ann" is
  // "ann-2"); `fallback` (the name it asked for) when it has no place in the match yet
  // or is a spectator.
  std::string shown_name(std::uint32_t player_id, const std::string& fallback) const;
  const std::string& record_path() const { return record_path_; }
  // How the intended ticks of input frames met the room's clock (PROTOCOL.md 4.5).
  const InputTiming& input_timing() const { return timing_; }
  // When the room last had a connected session (the host closes it after a while).
  std::uint64_t last_occupied_ms = 0;
  // Being handed over to a peer (GameHost::export_rooms): it steps, publishes and closes
  // for idling no more until the peer answers.
  bool frozen = false;
  // Adopted from a peer and not yet confirmed (GameHost::confirm_adopted): forgotten at
  // this time unless confirmed first; 0 once confirmed (or never adopted).
  std::uint64_t unconfirmed_until_ms = 0;
  // Its journal written and synced to the state now, a new segment beginning with a
  // checkpoint of it (a hand-over ships that segment). False without a journal or while
  // the journal fails or drops records. In two halves, for several rooms' writers to sync
  // at once: start_sync asks for it, finish_sync waits for it.
  void start_sync();
  bool finish_sync();
  // The host (address without port) whose hello made the room; "" for a resumed one.
  // Its open rooms count against it (Options::max_rooms_per_host).
  std::string maker_host;

 private:
  struct Held {
    protocol::InputFrame frame;  // latest frame by seq
    bool fire = false;           // any fire since the last tick
    std::uint64_t received_ms = 0;  // when the latest frame arrived (or came due)
    // Frames meant for a later tick (PROTOCOL.md 4.5), in arrival (= seq) order; at most
    // kMaxEarlyFrames: over it the oldest is applied at once.
    std::deque<protocol::InputFrame> early;
  };
  void hold(Held& h, const protocol::InputFrame& f, std::uint64_t now_ms);
  sim::TickInputs gather(std::uint64_t now_ms);
  void answer(const std::vector<sim::CommandResult>& results, protocol::ServerEndpoint& endpoint, std::uint64_t now_ms);
  void log_events(const std::vector<sim::Event>& events, protocol::ServerEndpoint& endpoint, std::uint64_t now_ms);
  void journal_session(const protocol::ServerEvent& e, const protocol::ServerEndpoint& endpoint);
  void watch_journal();

  std::uint32_t id_;
  std::string code_;
  bool private_;
  std::uint64_t seed_;
  std::uint32_t input_expiry_ms_;
  room::RoomStepper stepper_;  // the match, its event numbering and recent window
  sim::TickOutput stepped_;    // the last step's results and events, until publish()
  sim::TickInputs pending_;  // connection events and commands for the next step
  sim::IdMap<std::uint32_t, Held> held_;
  InputTiming timing_;
  std::string record_path_;
  std::unique_ptr<store::JournalWriter> recorder_;
  std::uint32_t ticks_per_snapshot_ = 5;
  RateLimitedLog refused_log_{"purchase_refused"};  // a client can make refusals at will
  std::unique_ptr<store::JournalWriter> journal_;
  std::uint64_t journal_dropped_logged_ = 0;
  std::uint64_t journal_failures_ = 0;  // as last seen (logged)
  bool journal_failing_ = false;        // as last seen, once a second
  std::string journal_error_;
  Stats::Totals* totals_ = nullptr;
  void push_result(const profiles::MatchResult& r);
  void journal_careers(const std::vector<std::uint32_t>& players, const protocol::ServerEndpoint& endpoint);
  Careers careers_;
  profiles::Writer* profiles_ = nullptr;
  std::function<std::int64_t()> unix_s_;
  std::map<std::uint32_t, store::JournalSession> journaled_;  // each player's last session record
};

// The result code (PROTOCOL.md 4.7) of the match's answer to a command.
protocol::ResultCode refusal_code(sim::Refusal r);

}  // namespace fts::server
