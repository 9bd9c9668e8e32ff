// One scripted bot: an ordinary client of the public protocol (no back door). Sans-I/O
// like the protocol itself: the process feeds it datagrams and the time, and sends what
// it takes out; fts-bot runs K of them over K sockets.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bot/script.hpp"
#include "fts/protocol/client.hpp"
#include "fts/sim/rng.hpp"

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
  // The session token once welcomed ("" before).
  const std::string& token() const { return token_; }
  nlohmann::ordered_json report() const;

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
  std::optional<protocol::ClientEndpoint> endpoint_;
  sim::Rng rng_;
  std::optional<protocol::Snapshot> latest_;
  std::uint32_t player_id_ = 0;
  std::string token_;
  std::uint32_t first_tick_ = 0, last_tick_ = 0;
  std::uint64_t last_input_ms_ = 0;
  std::uint64_t snapshots_ = 0;
  std::uint32_t ticks_per_snapshot_ = 5;
  std::uint32_t last_event_tick_ = 0;
  std::vector<std::string> new_events_;  // names of events seen since the last update
  std::vector<double> rtt_samples_;
  std::uint64_t last_rtt_sample_ms_ = 0;
  // Commands in flight and their results.
  std::uint32_t pending_rid_ = 0;
  protocol::CommandOp pending_op_ = protocol::CommandOp::ready;
  char pending_item_ = 0;
  bool command_sent_ = false;
  bool reconnect_started_ = false;
  std::optional<protocol::Result> last_result_;
  std::uint64_t purchases_ok_ = 0, purchases_refused_ = 0;
  std::vector<std::string> bought_;
  bool sent_ready_for_phase_ = false;
  protocol::Phase last_phase_ = protocol::Phase::lobby;
  std::uint32_t shop_wait_tick_ = 0;  // shopper: decide again after a snapshot past this tick
  // Script state.
  std::size_t pc_ = 0;
  bool step_started_ = false;
  std::uint64_t step_deadline_ms_ = 0;
  std::uint32_t step_until_tick_ = 0;
  double timeout_s_ = 60;
  bool script_hunting_ = false;
  protocol::InputFrame script_hold_;
  bool fire_once_ = false;
  bool disconnected_by_script_ = false;
  std::int64_t earned_ = 0, spent_ = 0;
  std::uint64_t purchase_events_ = 0;
  std::vector<std::string> errors_;
  std::string failure_;
  bool finished_ = false;
  std::uint64_t now_ms_ = 0;
  std::uint64_t wander_until_tick_ = 0;
  protocol::InputFrame wander_;
};

std::optional<Behavior> parse_behavior(const std::string& s);

}  // namespace fts::bot
