// The server without its socket: connections (protocol::ServerEndpoint), the match and
// the glue between them. The UDP loop feeds it datagrams and calls tick() at the fixed
// rate; everything here is driven by the time passed in, so tests step it by hand.
#pragma once

#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/chat_relay.hpp"
#include "app/log.hpp"
#include "app/options.hpp"
#include "app/stats.hpp"
#include "fts/protocol/server.hpp"
#include "fts/sim/match.hpp"
#include "host/journal.hpp"
#include "host/record.hpp"

namespace fts::server {

class GameHost {
 public:
  GameHost(const Options& options, const sim::MatchConfig& config, const protocol::ServerKey& key);

  // Writes the input log and hashes (--record) to `out` from now on.
  void record_to(std::ostream& out, const std::string& version);

  // ---- crash-safe journal (issue 15): a room's hooks, kept together for the rooms merge.
  // Resumes the room from its journal (read_journal): the match, the event numbering and
  // the sessions (away until their clients come back with their tokens).
  void resume_from(const host::ResumedRoom& room, std::uint64_t now_ms);
  // Journals this room from now on (a new segment starting with a checkpoint).
  void journal_to(host::JournalConfig config);
  const host::JournalWriter* journal() const { return journal_.get(); }
  host::JournalWriter* journal() { return journal_.get(); }
  // The wire events of one step (for read_journal's event numbering).
  static std::uint32_t wire_event_count(std::int64_t tick, const sim::TickOutput& out);

  void receive(const std::string& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms);
  // One simulation tick: connection events, inputs and commands in, step, results and
  // (when due) snapshots out.
  void tick(std::uint64_t now_ms);
  // Tells every client the server stops.
  void shutdown(std::uint64_t now_ms);
  std::vector<protocol::Outgoing> take_datagrams();

  const sim::MatchState& match() const { return match_; }
  const protocol::ServerEndpoint& endpoint() const { return endpoint_; }
  Stats& stats() { return stats_; }
  // While draining, a new player is refused (error "draining"); reconnects still resume.
  void set_draining(bool draining) { draining_ = draining; }
  bool draining() const { return draining_; }

 private:
  struct Held {
    protocol::InputFrame frame;  // latest frame by seq
    bool fire = false;           // any fire since the last tick
    std::uint64_t received_ms = 0;  // when the latest frame arrived
  };
  sim::TickInputs gather(std::uint64_t now_ms);
  // Forwards the step's result of each command to the client that sent it.
  void answer(const std::vector<sim::CommandResult>& results, std::uint64_t now_ms);
  void log_events(const std::vector<sim::Event>& events, std::uint64_t now_ms);
  void send_snapshots(std::uint64_t now_ms);
  // A chat command: refused, or relayed to every connected player (chat_relay.hpp).
  void relay_chat(const protocol::PlayerCommand& pc, std::uint64_t now_ms);

  Options options_;
  sim::MatchState match_;
  protocol::ServerEndpoint endpoint_;
  std::map<std::uint32_t, Held> held_;
  ChatRelay chat_;
  std::vector<sim::JoinRequest> joins_;
  std::vector<sim::PlayerId> leaves_;
  std::deque<protocol::Event> recent_;
  std::uint32_t event_seq_ = 0;
  std::uint64_t stalled_logged_ms_ = 0;  // seq of the newest event sent (PROTOCOL.md 8.4)
  std::unique_ptr<host::RecordWriter> recorder_;
  void journal_session(const protocol::ServerEvent& e);
  void watch_journal();
  std::unique_ptr<host::JournalWriter> journal_;
  std::uint64_t journal_dropped_logged_ = 0;
  bool journal_error_logged_ = false;
  std::uint32_t ticks_per_snapshot_ = 5;
  sim::Phase last_phase_ = sim::Phase::lobby;
  Stats stats_;
  bool draining_ = false;
  RateLimitedLog refused_log_{"purchase_refused"};  // a client can make refusals at will
};

protocol::ServerConfig make_endpoint_config(const Options& options, const sim::MatchConfig& config,
                                            const protocol::ServerKey& key);

}  // namespace fts::server
