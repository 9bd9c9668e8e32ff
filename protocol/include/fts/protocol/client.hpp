// The client end of a connection, sans-I/O: feed it received datagrams and the time,
// take the datagrams it wants sent. It runs the handshake (hello, challenge, hello with
// cookie, welcome), sends redundant inputs, resends commands until acknowledged,
// reassembles snapshots and acknowledges them.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fts/protocol/ack.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/reliable.hpp"
#include "fts/protocol/snapshot_delta.hpp"

namespace fts::protocol {

struct ClientConfig {
  Encoding encoding = Encoding::msgpack;
  std::string name = "player";  // 1..16 printable ASCII
  std::string token;            // a previous welcome's token, to take a player back
  std::string join;             // Hello::join: "" (quick), "quick", "create", "join", "spectate"
  std::string room;             // Hello::room: the code for join and spectate
  // Names one connection attempt in its hellos (Hello::nonce). 0: a random one, new at
  // every connect().
  std::uint64_t nonce = 0;
  std::uint16_t version = kProtocolVersion;
  std::uint64_t hello_resend_ms = 250;
  std::uint64_t connect_timeout_ms = 10000;
  std::uint64_t heartbeat_ms = 100;  // send at least this often once connected
  std::uint64_t resend_ms = 100;     // resend an unacknowledged command after this
  std::size_t input_redundancy = 8;  // input frames per datagram (the welcome may raise it)
};

enum class ClientState { idle, connecting, connected, refused, timed_out, disconnected };
const char* to_string(ClientState state);

struct ClientStats {
  std::uint64_t datagrams_sent = 0, datagrams_received = 0;
  std::uint64_t bytes_sent = 0, bytes_received = 0;
  std::uint64_t snapshots_received = 0;  // complete snapshots
  double rtt_ms = 0;
};

class ClientEndpoint {
 public:
  explicit ClientEndpoint(ClientConfig config = {});

  // Starts (or restarts) the handshake.
  void connect(std::uint64_t now_ms);
  // One datagram from the server.
  void receive(std::span<const std::uint8_t> bytes, std::uint64_t now_ms);
  // Timers: hello resends, heartbeats, command resends, time-outs. Call every few ms.
  void update(std::uint64_t now_ms);

  // Queues the input of one tick (its seq is assigned here and returned) and sends a
  // datagram with the latest few frames. Ignored unless connected (returns 0).
  std::uint32_t send_input(InputFrame frame, std::uint64_t now_ms);
  // Queues a reliable command and sends it; returns its rid (0 unless connected).
  std::uint32_t send_command(CommandOp op, char item, std::uint64_t now_ms);
  // Clean disconnect: sends bye (three times, it is not acknowledged).
  void disconnect(std::uint64_t now_ms, const std::string& reason = "quit");

  // Datagrams to send to the server, oldest first.
  std::vector<std::vector<std::uint8_t>> take_datagrams();
  // Command results, in order, each exactly once.
  std::vector<Result> take_results();
  // Complete snapshots, newest last (older ones that arrive late are dropped).
  std::vector<Snapshot> take_snapshots();
  // The match's events, each exactly once, in seq order (however often snapshots repeat
  // them).
  std::vector<Event> take_events() { return snapshots_.take_events(); }

  ClientState state() const { return state_; }
  const std::optional<Welcome>& welcome() const { return welcome_; }
  const std::optional<Error>& error() const { return error_; }
  const Snapshot* latest_snapshot() const { return snapshots_.latest(); }
  const RejectCounters& rejects() const { return rejects_; }
  ClientStats stats() const;

 private:
  void send_hello(std::uint64_t now_ms);
  void send_packet(std::uint64_t now_ms);
  void emit(const Header& header, const std::vector<Message>& messages);
  void handle_connected(const Datagram& d, std::uint64_t now_ms);
  void reject(Reject reason) { rejects_.add(reason); }

  ClientConfig config_;
  ClientState state_ = ClientState::idle;
  std::string cookie_;
  std::string nonce_;  // 16 hex digits
  std::uint64_t connect_start_ms_ = 0;
  std::uint64_t last_hello_ms_ = 0;
  std::uint64_t last_send_ms_ = 0;
  std::uint64_t last_receive_ms_ = 0;
  std::uint64_t timeout_ms_ = 10000;
  std::uint32_t session_ = 0;
  std::optional<Welcome> welcome_;
  std::optional<Error> error_;
  AckWindow acks_;
  ReliableSender<Command> commands_;
  ReliableReceiver<Result> results_;
  SnapshotReceiver snapshots_;
  std::vector<Snapshot> new_snapshots_;
  std::deque<InputFrame> inputs_;
  std::uint32_t next_input_seq_ = 1;
  std::vector<std::vector<std::uint8_t>> out_;
  RejectCounters rejects_;
  ClientStats stats_;
};

}  // namespace fts::protocol
