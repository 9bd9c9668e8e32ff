// One client's session on the server (issue 39): everything one client's datagrams touch,
// kept by the endpoint (server.hpp) in its table of sessions by player id. A datagram
// from a client goes through four places, each findable by name:
//   screened  ServerEndpoint::screen (server.cpp): the sender (screen_sender: its host's
//             rate, the header, the version), then the session its id names and the
//             address it must come from (session_for, below: at once, or in the InboxJob
//             of a queued datagram); a handshake datagram goes to handle_hello
//             (server_handshake.cpp) instead, whose Handshake (handshake.hpp) checks what
//             the hello proves;
//   opened    open_sealed with the session's `seal` (its keys and replay window): at once
//             in receive(), or on a worker in an InboxJob (server_jobs.hpp);
//   applied   ServerSession::apply (server_session.cpp), on the session's own: its rate,
//             acks, inputs, commands exactly once, bye; what it leaves for everyone
//             (an Applied) is settled by ServerEndpoint::settle (server_inbox.cpp), in
//             arrival order;
//   answered  seal_packet / seal_snapshots (server.cpp; heartbeats and resends by the
//             room's TimerJob, server_timers.cpp), each datagram stamped by next_header
//             and sealed by seal_into below.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <unordered_map>
#include <string>
#include <vector>

#include "fts/protocol/ack.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/codes.hpp"
#include "fts/protocol/header.hpp"
#include "fts/protocol/limits.hpp"
#include "fts/protocol/reject.hpp"
#include "fts/protocol/reliable.hpp"
#include "fts/protocol/seal.hpp"
#include "fts/protocol/session_id_index.hpp"
#include "fts/protocol/snapshot_delta.hpp"

namespace fts::protocol {

// Addresses are opaque strings ("127.0.0.1:5000"), made by the caller from its sockets.
using Address = std::string;

// A datagram to send: where, and its bytes.
struct Outgoing {
  Address to;
  std::vector<std::uint8_t> bytes;
};

struct ServerConfig;

// What the game takes from the sessions (ServerEndpoint::take_inputs, take_commands).
struct PlayerInput {
  std::uint32_t player_id = 0;
  std::uint32_t room = 0;
  InputFrame frame;  // each (player, seq) delivered at most once, ascending seq
};

struct PlayerCommand {
  std::uint32_t player_id = 0;
  std::uint32_t room = 0;
  Command command;  // each exactly once, in rid order
};

// What applying one datagram to its session leaves for the endpoint, which shares it with
// every other session: the game's inputs and commands, and whether the datagram ended the
// session. Filled by ServerSession::apply (on any thread: it touches that session only),
// settled by the endpoint in its serial part, in the datagrams' arrival order.
struct Applied {
  enum class End : std::uint8_t { none, bye, overflow };
  std::vector<PlayerInput> inputs;
  std::vector<PlayerCommand> commands;
  End end = End::none;
  std::string why;  // a bye's reason; an overflow's queue ("commands", "results")
  void clear() {
    inputs.clear();
    commands.clear();
    end = End::none;
    why.clear();
  }
};

struct ServerSession {
  std::uint32_t player_id = 0;
  std::string name;
  std::string token;     // "" for a restored session until its client comes back
  std::string verifier;  // token_verifier(token)
  std::string identity;  // the proven identity's fingerprint ("" a guest)
  std::uint32_t session_id = 0;
  Address address;
  Encoding encoding = Encoding::msgpack;
  bool connected = false;
  bool quit = false;  // left with bye "quit": its seat is free, its progress kept
  std::string nonce;  // the connection attempt this session was started by (Hello::nonce)
  bool welcomed_as_reconnect = false;
  std::uint64_t last_receive_ms = 0;
  std::uint64_t last_send_ms = 0;
  std::uint64_t disconnected_ms = 0;
  std::uint32_t last_input_seq = 0;
  std::vector<std::uint16_t> acked_scratch;  // apply's: our sequences a header acknowledged
  std::size_t unanswered = 0;  // commands handed to the game, not yet answered
  std::uint64_t last_active_ms = 0;  // last real input (idle time-out)
  bool played = false;  // sent real input once: a lost connection holds its slot
  std::uint64_t rate_limited = 0;
  TokenBucket datagrams;
  SealedChannel seal;  // this session's keys and replay window (PROTOCOL.md 5.7)
  AckWindow acks;
  ReliableSender<Result> results;
  ReliableSender<Chat> chats;
  ReliableReceiver<Command> commands;
  SnapshotSender snapshots;
  std::uint32_t room = 0;
  std::string room_code;
  bool spectator = false;  // no seat; inputs dropped; never idle
  bool watching = false;   // out of lives (RoomSessions::set_watching): never idle
  bool kept = false;       // past its reconnect window, kept while its room's match runs

  // Applies an opened datagram of this session (`opened` its decoding or why it did not
  // decode): its rate, acks, inputs (ahead of the last applied, by at most
  // config.max_input_lead) and commands, each exactly once; a command whose field did not
  // read is answered here. Touches this session, `out` and `rejects` only: sessions on
  // different threads apply at once. After a bye or an overflow (out.end) the session takes
  // nothing more; the endpoint ends it.
  void apply(const Decoded<Datagram>& opened, std::uint64_t now_ms, const ServerConfig& config, Applied& out,
             RejectCounters& rejects);
  // Queues the result of command `rid` (its text cut to printable ASCII and kMaxTextBytes);
  // false when the results waiting for the client's acks are over `max_pending` (an overflow).
  bool answer(std::uint32_t rid, ResultCode code, std::string message, std::size_t max_pending);
  // One input frame, in sequence order: applied if newer than the last and not too far ahead.
  void take_frame(const InputFrame& f, std::uint64_t now_ms, const ServerConfig& config, Applied& out,
                  RejectCounters& rejects);

  // The header of this session's next datagram: its encoding and id, its acks stamped
  // (the sequence counts on).
  Header next_header(std::uint16_t version, std::uint64_t now_ms);
  // Seals `payload` under `h` for this session into the next datagram of `out`, reusing
  // the buffers of one from `spare` when there is one. Touches this session and the two
  // vectors only: rooms on different threads seal into lanes of their own.
  void seal_into(const Header& h, const std::vector<std::uint8_t>& payload, std::vector<Outgoing>& out,
                 std::vector<Outgoing>& spare);
};

// The session a sealed datagram from `from` may be opened for, `found` being the session
// its header's id names (nullptr: none): connected, at that address; otherwise nullptr and
// why counted (unknown_session, address_mismatch). screen() and an InboxJob ask it.
ServerSession* session_for(ServerSession* found, const Address& from, RejectCounters& rejects);

// The connected sessions whose session ids fall in one shard of kShards (a multiplicative
// hash's top bits): what an InboxJob may reach. It finds no session of another shard, so
// two jobs holding two shards never touch one session. Made by SessionTable::shard; valid
// while no session is indexed or unindexed (none is while jobs run).
class SessionShard {
 public:
  static constexpr unsigned kShardBits = 6;
  static constexpr unsigned kShards = 1u << kShardBits;
  static unsigned of(std::uint32_t session_id) { return (session_id * 0x9E3779B1u) >> (32 - kShardBits); }
  unsigned number() const { return shard_; }
  // The connected session `session_id` names, if it is of this shard; nullptr otherwise.
  ServerSession* find(std::uint32_t session_id) const {
    return index_ != nullptr && of(session_id) == shard_ ? index_->find(session_id) : nullptr;
  }

 private:
  friend class SessionTable;
  const SessionIdIndex<ServerSession>* index_ = nullptr;
  unsigned shard_ = 0;
};

// The endpoint's sessions (issue 39): by player id, indexed by the address and the
// session id of each connected one (what screen() looks a datagram up by), and the player
// ids given so far. Iterates and finds like the map it wraps; the indexes change only
// through index and unindex.
class SessionTable {
 public:
  using Map = std::map<std::uint32_t, ServerSession>;

  explicit SessionTable(std::uint32_t first_player_id = 1) : next_player_id_(first_player_id == 0 ? 1 : first_player_id) {}
  // Not copied: the indexes point into this table's sessions (a move keeps them in place).
  SessionTable(const SessionTable&) = delete;
  SessionTable& operator=(const SessionTable&) = delete;
  SessionTable(SessionTable&&) = default;
  SessionTable& operator=(SessionTable&&) = default;

  Map::iterator begin() { return by_id_.begin(); }
  Map::iterator end() { return by_id_.end(); }
  Map::const_iterator begin() const { return by_id_.begin(); }
  Map::const_iterator end() const { return by_id_.end(); }
  std::size_t size() const { return by_id_.size(); }
  std::size_t count(std::uint32_t player_id) const { return by_id_.count(player_id); }
  Map::iterator find(std::uint32_t player_id) { return by_id_.find(player_id); }
  Map::const_iterator find(std::uint32_t player_id) const { return by_id_.find(player_id); }
  ServerSession& at(std::uint32_t player_id) { return by_id_.at(player_id); }
  // A new session (or the one there is) with this player id, not indexed yet.
  ServerSession& operator[](std::uint32_t player_id) {
    ++generation_;
    return by_id_[player_id];
  }
  // Removes the session, and its entries in the indexes.
  void erase(Map::iterator it) {
    unindex(it->second);
    by_id_.erase(it);
  }
  // Moves on whenever a session is made, indexed, unindexed or erased: the set of connected
  // sessions (and where they live) is the same as long as it does not.
  std::uint64_t generation() const { return generation_; }

  // The connected session at `address`, or with session id `id` (nullptr: none).
  ServerSession* at_address(const Address& address);
  ServerSession* with_session_id(std::uint32_t id);
  // A read-only view of the sessions of shard `n` (below SessionShard::kShards) by id.
  SessionShard shard(unsigned n) const {
    SessionShard v;
    v.index_ = &by_session_id_;
    v.shard_ = n;
    return v;
  }
  bool session_id_taken(std::uint32_t id) const { return by_session_id_.find(id) != nullptr; }
  // The session's address and session id are its own in the indexes from now on; unindex
  // takes them out (the session stays, disconnected or gone).
  void index(ServerSession& s);
  void unindex(const ServerSession& s);

  // Player ids (ServerEndpoint::reserve_player_ids and take_player_id say why): the next
  // new session's, none at or below `id` from now on, one id no newcomer gets.
  static constexpr std::uint32_t kNoPlayerIdLeft = 0xFFFFFFFFu;
  std::uint32_t next_player_id();  // kNoPlayerIdLeft when they ran out
  void reserve_player_ids(std::uint32_t id) {
    if (id >= next_player_id_) next_player_id_ = id >= kNoPlayerIdLeft - 1 ? kNoPlayerIdLeft : id + 1;
  }
  void take_player_id(std::uint32_t id) {
    if (id != 0 && id >= next_player_id_ && id != kNoPlayerIdLeft) taken_player_ids_.insert(id);
  }

 private:
  Map by_id_;
  // Hashed, to the session in by_id_ (a map's nodes stay put): every datagram is looked
  // up by its session id (by an InboxJob, through its shard, on the pool).
  std::unordered_map<Address, ServerSession*> by_address_;
  SessionIdIndex<ServerSession> by_session_id_;
  std::uint64_t generation_ = 0;
  std::uint32_t next_player_id_ = 1;
  std::set<std::uint32_t> taken_player_ids_;  // ids above next_player_id_ taken by rooms from elsewhere
};

}  // namespace fts::protocol
