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
#include <utility>
#include <vector>

#include "fts/protocol/ack.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/codes.hpp"
#include "fts/protocol/identity.hpp"
#include "fts/protocol/reliable.hpp"
#include "fts/protocol/seal.hpp"
#include "fts/protocol/snapshot_delta.hpp"

namespace fts::protocol {

struct ClientConfig {
  Encoding encoding = Encoding::msgpack;
  std::string name = "player";  // 1..16 printable ASCII
  std::string token;            // a previous welcome's token, to take a player back (sent sealed)
  std::string join;             // Hello::join: "" (quick), "quick", "create", "join", "spectate"
  std::string room;             // Hello::room: the code for join and spectate
  // The player's long-term identity, proven in the cookie hello (PROTOCOL.md 5.8); none:
  // a guest.
  std::optional<Identity> identity;
  // Names one connection attempt in its hellos (Hello::nonce). 0: a random one, new at
  // every connect().
  std::uint64_t nonce = 0;
  std::uint16_t version = kProtocolVersion;
  std::uint64_t hello_resend_ms = 250;
  std::uint64_t connect_timeout_ms = 10000;
  std::uint64_t heartbeat_ms = 100;  // send at least this often once connected
  std::uint64_t resend_ms = 100;     // resend an unacknowledged command after this
  std::size_t input_redundancy = 3;  // input frames per datagram (the welcome may raise it)
  // The lean uplink (hold_input): a changed input goes out at most this often, an
  // unchanged one at least this often (the server's input expiry is 150 ms).
  std::uint64_t input_min_interval_ms = 20;
  std::uint64_t input_keepalive_ms = 50;
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
  // The lean uplink: the input the player holds now, passed every tick. A new frame is
  // sent when the input changes or fires (at most every input_min_interval_ms; a change
  // in between goes out at a later call, a fire is kept until then) and at least every
  // input_keepalive_ms while it stays the same. Returns the seq sent now (0: none).
  std::uint32_t hold_input(InputFrame frame, std::uint64_t now_ms);
  // Queues a reliable command and sends it; returns its rid (0 unless connected).
  std::uint32_t send_command(CommandOp op, char item, std::uint64_t now_ms);
  // Queues a chat line (a reliable command "chat"); returns its rid (0 unless connected).
  // Bytes outside printable ASCII are sent as '?'.
  std::uint32_t send_chat(const std::string& text, std::uint64_t now_ms);
  // Clean disconnect: sends bye (three times, it is not acknowledged).
  void disconnect(std::uint64_t now_ms, const std::string& reason = "quit");

  // Datagrams to send to the server, oldest first.
  std::vector<std::vector<std::uint8_t>> take_datagrams();
  // Command results, in order, each exactly once.
  std::vector<Result> take_results();
  // Chat lines and host announcements, in order, each exactly once.
  std::vector<Chat> take_chats() { return chats_.take(); }
  // Leaderboards received (PROTOCOL.md 4.7c), oldest first; each `cmd` names its request.
  std::vector<Leaderboard> take_boards() { return std::exchange(boards_, {}); }
  // Complete snapshots, newest last (older ones that arrive late are dropped).
  std::vector<Snapshot> take_snapshots();
  // The match's events, each exactly once, in seq order (however often snapshots repeat
  // them).
  std::vector<Event> take_events() { return snapshots_.take_events(); }

  ClientState state() const { return state_; }
  const std::optional<Welcome>& welcome() const { return welcome_; }
  const std::optional<Error>& error() const { return error_; }
  // The server said the room moved (PROTOCOL.md 4.9b): where to; the state is disconnected.
  const std::optional<Moved>& moved() const { return moved_; }
  const Snapshot* latest_snapshot() const { return snapshots_.latest(); }
  const RejectCounters& rejects() const { return rejects_; }
  // The server's datagrams dropped because they did not open (forged or replayed).
  const SealDrops& sealed_drops() const { return seal_.drops(); }
  // This attempt's session keys (PROTOCOL.md 5.7; zero before a challenge): for tools and
  // tests that write or read a session's datagrams themselves.
  const SessionKeys& session_keys() const { return keys_; }
  ClientStats stats() const;

 private:
  void send_hello(std::uint64_t now_ms);
  void send_packet(std::uint64_t now_ms);
  void emit(const Header& header, const std::vector<Message>& messages);
  void handle_connected(const Datagram& d, std::uint64_t now_ms);
  void handle_connecting(const Datagram& d, std::uint64_t now_ms);
  void reject(Reject reason) { rejects_.add(reason); }

  ClientConfig config_;
  ClientState state_ = ClientState::idle;
  std::string cookie_;
  KxKeyPair kx_;          // new for every connect(): the hello carries its public half
  SessionKeys keys_;      // from our key pair and the challenge's server key
  KxPublicKey server_kx_{};  // the challenge's key (the identity proof signs it)
  SealedChannel seal_;    // ready once a challenge gave the server's key
  std::vector<std::uint8_t> plain_;  // scratch: the payload of the datagram being opened
  std::string nonce_;  // 16 hex digits
  std::uint64_t connect_start_ms_ = 0;
  std::uint64_t last_hello_ms_ = 0;
  std::uint64_t last_send_ms_ = 0;
  std::uint64_t last_receive_ms_ = 0;
  std::uint64_t timeout_ms_ = 10000;
  std::uint32_t session_ = 0;
  std::optional<Welcome> welcome_;
  std::optional<Error> error_;
  std::optional<Moved> moved_;
  AckWindow acks_;
  ReliableSender<Command> commands_;
  ReliableReceiver<Result> results_;
  ReliableReceiver<Chat> chats_;
  std::vector<Leaderboard> boards_;  // at most kMaxBoards kept until taken
  static constexpr std::size_t kMaxBoards = 4;
  SnapshotReceiver snapshots_;
  std::vector<Snapshot> new_snapshots_;
  std::deque<InputFrame> inputs_;
  std::optional<InputFrame> last_held_;  // hold_input: the frame sent last
  std::uint64_t last_held_ms_ = 0;
  bool fire_pending_ = false;
  std::uint32_t next_input_seq_ = 1;
  std::vector<std::vector<std::uint8_t>> out_;
  RejectCounters rejects_;
  ClientStats stats_;
};

}  // namespace fts::protocol
