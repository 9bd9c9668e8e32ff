// One scripted bot: an ordinary client of the public protocol (no back door). Sans-I/O
// like the protocol itself: the process feeds it datagrams and the time, and sends what
// it takes out; fts-bot runs K of them over K sockets.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bot/script.hpp"
#include "bot/tally.hpp"
#include "fts/protocol/connection.hpp"
#include "fts/sim/rng.hpp"
#include "net/link_stats.hpp"
#include "net/net_timing.hpp"

namespace fts::bot {

enum class Behavior { idle, wander, hunter, shopper };

struct BotOptions {
  std::string name = "bot";
  Behavior behavior = Behavior::hunter;
  std::vector<Step> script;  // empty: just the behavior
  protocol::Encoding encoding = protocol::Encoding::msgpack;
  std::uint64_t seed = 1;
  std::string token;         // take a previous player back
  bool probe = false;        // done at the first snapshot
  std::uint16_t protocol_version = 0;  // 0: ours; other values test the server's refusal
  std::string join;  // Hello::join: "" (quick), "quick", "create", "join", "spectate"
  std::string room;  // the room code for join and spectate
  bool predict = false;  // predict the own ball and stamp frames with their tick (issue 28)
  bool predict_own_only = false;  // --predict-own-only: the own ball alone (no collisions; before issue 37)
  client::RemotePlayers predict_remote = client::kDefaultRemotePlayers;  // --predict-remote
  std::optional<protocol::Identity> identity;  // none: a guest (PROTOCOL.md 5.8)
};

// Where a bot is in its script, and what the script holds it to.
struct ScriptCursor {
  std::size_t pc = 0;  // the step being run
  bool step_started = false;
  std::uint64_t step_deadline_ms = 0;
  std::uint32_t step_until_tick = 0;
  double timeout_s = 60;          // "timeout S": how long a step may take
  bool command_sent = false;      // the step's command is in flight
  bool reconnect_started = false;
  bool hunting = false;           // "hunt": the hunter's input instead of `hold`
  protocol::InputFrame hold;      // "move": the input held until the step ends
  bool fire_once = false;
  bool disconnected = false;      // "disconnect": a bye we asked for is no failure
};

// The wander behavior: a random direction, held for a random 20..80 ticks.
class Wander {
 public:
  protocol::InputFrame input(std::uint32_t tick, sim::Rng& rng);

 private:
  std::uint64_t until_tick_ = 0;
  protocol::InputFrame frame_;
};

class Bot {
 public:
  explicit Bot(BotOptions options);

  void start(std::uint64_t now_ms);
  void receive(std::span<const std::uint8_t> bytes, std::uint64_t now_ms);
  // Timers, snapshots, results, the script and the behavior. Call every few ms.
  void update(std::uint64_t now_ms);
  // Ends the bot (end of --duration): a clean bye.
  void stop(std::uint64_t now_ms);
  std::vector<std::vector<std::uint8_t>> take_datagrams();

  bool finished() const { return finished_; }
  bool failed() const { return !failure_.empty(); }
  const std::string& failure() const { return failure_; }
  // The session token once welcomed ("" before, unless the options gave one).
  const std::string& token() const { return conn_.token(); }
  // One more for each connection attempt: the caller sends each from a fresh socket.
  std::uint64_t attempt() const { return conn_.attempt(); }
  // Where the room moved (PROTOCOL.md 4.9b; "" if it did not) and how often: the caller
  // sends the next attempt there.
  const std::string& moved_to() const { return conn_.moved_to(); }
  std::uint64_t moves() const { return conn_.moves(); }
  nlohmann::ordered_json report() const;
  // The code of the room the server put us in ("" before the welcome).
  std::string room() const;

 private:
  const protocol::PlayerState* me() const;
  void on_snapshot(const protocol::Snapshot& s);
  void run_script(std::uint64_t now_ms);
  bool step_script(const Step& s, std::uint64_t now_ms);  // true: step done
  protocol::InputFrame behave();
  void send_command(protocol::CommandOp op, char item, std::uint64_t now_ms);
  void fail(const std::string& why);
  double field(const std::string& name) const;

  BotOptions options_;
  protocol::ClientConnection conn_;
  std::uint64_t seen_attempt_ = 0;  // the connection attempt whose commands we wait for
  std::uint64_t seen_welcome_ = 0;  // --predict: the attempt whose welcome set the prediction up
  sim::Rng rng_;
  std::optional<protocol::Snapshot> latest_;
  Tally tally_;  // the report's figures
  std::uint32_t player_id_ = 0;
  std::uint64_t last_input_ms_ = 0;
  std::uint32_t ticks_per_snapshot_ = 5;
  std::uint32_t last_event_seq_ = 0;
  std::vector<std::string> new_events_;  // names of events seen since the last update
  // Commands in flight and their results.
  std::uint32_t pending_rid_ = 0;
  protocol::CommandOp pending_op_ = protocol::CommandOp::ready;
  char pending_item_ = 0;
  std::uint64_t commands_sent_ = 0;      // commands given a rid (each to be applied exactly once)
  std::uint64_t commands_answered_ = 0;  // results received for them
  std::optional<protocol::Result> last_result_;
  bool sent_ready_for_phase_ = false;
  protocol::Phase last_phase_ = protocol::Phase::lobby;
  std::uint32_t shop_wait_tick_ = 0;  // shopper: decide again after a snapshot past this tick
  ScriptCursor script_;
  std::vector<std::string> errors_;
  std::string failure_;
  bool finished_ = false;
  Wander wander_;
  std::string refused_as_expected_;  // "expect room refused CODE" met: the refusal's code
  // (tick, digest of the snapshot's balls and players) of the latest snapshots: a
  // spectator and a player of one room report the same digests for the same ticks.
  std::deque<std::pair<std::uint32_t, std::string>> digests_;
  // --predict: what fts-client runs for its own ball (predict/prediction.hpp).
  client::NetTiming net_;
  // Wall time spent in the prediction (the snapshot's reconciliation and each frame's
  // prediction), microseconds per call, for the report.
  std::vector<double> predict_frame_us_, predict_snapshot_us_;
  std::uint64_t now_ms_ = 0;
};

std::optional<Behavior> parse_behavior(const std::string& s);
// A phase as scripts (wait_phase) and reports name it: lobby, play, shop, over.
const char* phase_name(protocol::Phase p);

}  // namespace fts::bot
