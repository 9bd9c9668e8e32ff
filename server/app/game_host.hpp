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
#include "host/record.hpp"

namespace fts::server {

class GameHost {
 public:
  GameHost(const Options& options, const sim::MatchConfig& config, const protocol::ServerKey& key);

  // Writes the input log and hashes (--record) to `out` from now on.
  void record_to(std::ostream& out, const std::string& version);

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
  std::uint32_t ticks_per_snapshot_ = 5;
  sim::Phase last_phase_ = sim::Phase::lobby;
  Stats stats_;
  RateLimitedLog refused_log_{"purchase_refused"};  // a client can make refusals at will
};

protocol::ServerConfig make_endpoint_config(const Options& options, const sim::MatchConfig& config,
                                            const protocol::ServerKey& key);

}  // namespace fts::server
