// The server end of every connection, sans-I/O: feed it (address, datagram, time), take
// the datagrams it wants sent and what the clients asked for. It answers hellos with
// stateless cookies, allocates a player only for a client that proved its address,
// keeps sessions alive (heartbeats, time-outs, reconnect by token), delivers commands
// exactly once and sends snapshots as deltas. Addresses are opaque strings
// ("127.0.0.1:5000"), made by the caller from its sockets. One client's state is a
// ServerSession (server_session.hpp, which also says where a datagram is screened,
// opened, applied and answered); the per-host limits are AddressLimits (limits.hpp).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <variant>
#include <vector>

#include "fts/protocol/ack.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/codes.hpp"
#include "fts/protocol/handshake.hpp"
#include "fts/protocol/cookie.hpp"
#include "fts/protocol/identity.hpp"
#include "fts/protocol/limits.hpp"
#include "fts/protocol/reliable.hpp"
#include "fts/protocol/seal.hpp"
#include "fts/protocol/server_jobs.hpp"
#include "fts/protocol/server_session.hpp"
#include "fts/protocol/snapshot_delta.hpp"

namespace fts::protocol {

class ServerEndpoint;

// A new player's choice of room (Hello::join, Hello::room), as the host sees it.
struct JoinAsk {
  std::string join;  // "" (quick), "quick", "create", "join", "spectate"
  std::string room;  // code for join and spectate
  Address from;
};

// The host's answer: the room the session belongs to, or a refusal (error code and a
// sentence) sent to the client instead of a welcome.
struct Admission {
  std::uint32_t room = 0;  // the host's room id (never 0 when admitted)
  std::string code;        // the room's code, sent in the welcome
  bool spectator = false;
  std::uint32_t server_tick = 0;  // the room's tick, sent in the welcome
  std::optional<ErrorCode> error;  // none: admitted; else room_full, no_such_room, server_full, ...
  std::string message;
};

struct ServerConfig {
  ServerKey key{};  // random_key() at start-up; fixed in tests
  std::uint16_t version = kProtocolVersion;
  std::uint32_t max_players = 8;
  std::uint64_t timeout_ms = 10000;
  std::uint64_t reconnect_window_ms = 60000;
  std::uint64_t cookie_lifetime_ms = 10000;
  std::uint64_t heartbeat_ms = 100;
  std::uint64_t resend_ms = 100;
  // A gap between two calls (receive/update) longer than this is the server's own stall,
  // not the clients' silence: it does not count towards time-outs (PROTOCOL.md 6).
  std::uint64_t stall_threshold_ms = 500;
  // An input frame more than this many sequence numbers ahead of the last one applied is
  // ignored (PROTOCOL.md 4.5).
  std::uint32_t max_input_lead = 1024;
  // A client whose newest acknowledged snapshot is older than this gets a full snapshot
  // instead of a delta (the host sets one second of ticks).
  std::uint32_t snapshot_max_base_age_ticks = 100;
  // The first player id this endpoint gives. A server of a fleet starts somewhere in a
  // large space (fts-server: from its random key) so that a room handed to a peer keeps
  // ids the peer's own players do not have (issue 42); alone, a server starts at 1.
  std::uint32_t first_player_id = 1;
  // Sessions kept at most (seated players plus players who quit and keep their progress
  // for the reconnect window).
  std::size_t max_sessions() const {
    return max_sessions_total != 0 ? max_sessions_total : 4 * static_cast<std::size_t>(max_players);
  }
  std::size_t max_sessions_total = 0;  // 0: 4 * max_players (one room)
  // Rooms (PROTOCOL.md 4.6), required (the constructor throws without it): a new
  // player's hello is passed to the host, which picks its room or refuses it. max_players
  // is a room's seats: the host checks them through seats_in_room; a player who quit and
  // comes back is held to them here (room_full).
  std::function<Admission(const JoinAsk&)> admit;
  // Bounds on what one session may make the server hold (PROTOCOL.md 10). A session over
  // either cap is dropped at once with error "overflow" (counted as overflow).
  // Results sent and not yet acknowledged by the client.
  std::size_t max_pending_results = 64;
  // Commands buffered out of order plus commands handed to the game and not yet answered.
  std::size_t max_pending_commands = 64;
  // Chat lines sent to one session and not yet acknowledged; a line over it is not sent
  // to that session (counted in chat_dropped()).
  std::size_t max_pending_chats = 32;
  // Datagram rates (token buckets); a datagram over a rate is dropped (rate_limited).
  // An honest client sends one input per tick (100/s) plus heartbeats and commands.
  std::uint32_t session_datagrams_per_s = 250;
  std::uint32_t session_datagram_burst = 250;
  // Per host (the address without its port), before anything else is looked at.
  std::uint32_t address_datagrams_per_s = 1000;
  std::uint32_t address_datagram_burst = 1000;
  // Hosts whose rates are tracked at most; past it, a new host is not rate limited until
  // quiet hosts are forgotten (once a second), so that a spoofed flood cannot lock out
  // new players.
  std::size_t max_tracked_addresses = 4096;
  // Fair slots. Seated sessions from one host (households share one NAT address); the
  // next new player from it gets error "address_full".
  std::size_t max_sessions_per_address = 4;
  // Spectators hold no seat; connected spectators from one host, apart from its seats.
  std::size_t max_spectators_per_address = 8;
  // Handshake datagrams (session 0) per host; over it they are dropped (rate_limited).
  std::uint32_t hellos_per_s = 10;
  std::uint32_t hello_burst = 10;
  // Hellos with a token (a reconnect takes its player over) per host; over it the hello
  // is refused with error "rate_limited" (counted as takeover_limited). The burst lets
  // every player of a household come back at once after an outage (0: as many as
  // max_sessions_per_address).
  std::uint32_t takeovers_per_s = 1;
  std::uint32_t takeover_burst = 0;
  // Room codes that name no open room (the host's admit answers no_such_room, counted
  // as unknown_room), per host and minute; past the burst, a join or spectate hello is
  // refused with error "rate_limited" before the code is looked at (counted as
  // code_limited). A code is 5 of 23 letters (6.4 million): at 6 a minute, one host
  // guesses one of 64 open rooms in 12 days on average. Quick play and create are free.
  std::uint32_t room_code_misses_per_min = 6;
  std::uint32_t room_code_miss_burst = 10;
  // A connected session that sends no real input (a frame with a key down, or a
  // command) for this long is dropped with error "idle"; never while the host says the
  // players cannot act (set_idle_paused: lobby, shop, game over). 0: never.
  std::uint64_t idle_timeout_ms = 120000;
  // Settings sent in every welcome (player_id, token, server_tick, reconnected are set
  // per client).
  Welcome settings;
};

struct ServerEvent {
  enum class Kind {
    connected,     // a new player (the match should add it)
    reconnected,   // a player came back with its token (same player id)
    disconnected,  // bye or time-out; the slot is held for the reconnect window
    released,      // the slot is free again (the match should remove the player)
  };
  Kind kind;
  std::uint32_t player_id = 0;
  std::string name;
  // For the host's log: the name of the ErrorCode the session was sent when one ended it
  // (kick, idle: to_string of codes.hpp's row, never spelled here), else how the link
  // ended ("timeout", the bye's reason, "replaced", "restart", "match over", ...); for a
  // reconnect, how the player was taken back: kByToken or kByIdentity.
  std::string reason;
  static constexpr const char* kByToken = "token";
  static constexpr const char* kByIdentity = "identity";
  bool quit = false;  // disconnected by the client's bye: its seat is free (PROTOCOL.md 5.4)
  std::uint32_t room = 0;
  bool spectator = false;
  std::string identity = "";  // the player's proven identity's fingerprint ("" a guest; PROTOCOL.md 5.8)
};

// A session carried over a server restart (from a room's journal): its player is away,
// its seat held for the reconnect window, and a hello whose token matches the verifier
// (token_verifier(token)) takes it back as a reconnect.
struct RestoredSession {
  std::uint32_t player_id = 0;
  std::string name;
  std::string token_verifier;
  bool quit = false;  // had given its seat up (bye or idle) before the restart
  std::string identity = "";  // its identity's fingerprint ("" a guest): a hello proving it takes it back too
  // A session of a room handed over by another server (issue 42): its id is that server's,
  // taken here (take_player_id) without moving this endpoint's own ids on to it.
  bool foreign = false;
};

struct SessionInfo {
  std::uint32_t player_id = 0;
  std::string name;
  Address address;
  bool connected = false;
  double rtt_ms = 0;
  std::optional<std::uint32_t> acked_snapshot;
  Encoding encoding = Encoding::msgpack;
  std::uint64_t rate_limited = 0;  // datagrams of this session dropped over its rate
  std::uint32_t room = 0;
  bool spectator = false;
  SealDrops sealed_drops;  // its sealed datagrams dropped: forged (bad tag) or replayed
  std::string identity = "";  // the fingerprint of its proven identity ("" a guest, PROTOCOL.md 5.8)
};

class ServerEndpoint {
 public:
  explicit ServerEndpoint(ServerConfig config);

  void receive(const Address& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms);

  // ---- Receiving on several threads (issues 29, 39). receive_later() makes receive()'s
  // checks of the sender at once (its host's rate, the header, the version: the one
  // shared part, AddressLimits; a handshake datagram is handled at once) and queues a
  // session's datagram by its session id's shard. inbox_jobs() hands out one InboxJob for
  // each shard with queued datagrams (server_jobs.hpp: the shard's sessions and its
  // datagrams, nothing else), to screen (session_for), open and apply on the pool while
  // nothing calls the endpoint. apply_inbox() then settles what they left (inputs,
  // commands, ended sessions) in arrival order, as receive() would have, and empties the
  // queue. At most kMaxInbox datagrams wait; beyond, they are dropped (rate_limited).
  void receive_later(const Address& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms);
  std::span<InboxJob* const> inbox_jobs();
  std::size_t inbox_datagrams() const { return inbox_used_; }
  void apply_inbox();
  static constexpr std::size_t kMaxInbox = 65536;
  // Timers: heartbeats, result resends, time-outs, idle players, reconnect windows. The
  // same in two halves for a pool (issue 39): timer_jobs() hands out a TimerJob for each
  // room with connected sessions (server_jobs.hpp: those sessions and a lane, no
  // endpoint), to run while nothing calls the endpoint; settle_timers() then queues their
  // datagrams in room order, ends the sessions they found silent or idle, and runs the
  // reconnect windows of the sessions not connected. update() is timer_jobs(), each run
  // here, and settle_timers().
  void update(std::uint64_t now_ms);
  std::span<TimerJob> timer_jobs(std::uint64_t now_ms);
  void settle_timers(std::uint64_t now_ms);

  // Sends the snapshot to one connected player (delta against what it acknowledged).
  void send_snapshot(std::uint32_t player_id, const Snapshot& snapshot, std::uint64_t now_ms);
  // The same for a snapshot quantized once per tick for every client (quantize()).
  void send_snapshot(std::uint32_t player_id, const SharedSnapshot& quantized, std::uint64_t now_ms);
  // (A room's snapshot job on the pool sends through its RoomSessions: connected_by_room.)
  // Queues a lane's datagrams after those queued already; the lane keeps buffers of sent
  // datagrams for its next ones.
  void adopt(SendLane& lane);
  // Answers a command (reliably): applied (ResultCode::ok, `ok: true`) or refused with
  // that code; message for a person. Queued: the timers' next run (update, timer_jobs)
  // sends the session's due results together in one datagram.
  void send_result(std::uint32_t player_id, std::uint32_t command_rid, ResultCode code, std::string message,
                   std::uint64_t now_ms);
  // Sends a leaderboard (PROTOCOL.md 4.7c) to a connected player, in a datagram of its
  // own (unreliable: the client asks again when it is lost). False: no such connected player.
  bool send_board(std::uint32_t player_id, const Leaderboard& board, std::uint64_t now_ms);
  // Ends a session now (error sent to the client, slot released).
  void kick(std::uint32_t player_id, ErrorCode code, const std::string& message, std::uint64_t now_ms);
  // Re-creates a session of a previous server process, disconnected as of now_ms (an
  // event `disconnected` with reason "restart" tells the host). A player id in use or a
  // bad verifier is refused (false), changing nothing.
  // `room` / `room_code`: the host's room the session belongs to (0: a server without rooms).
  bool restore_session(const RestoredSession& restored, std::uint64_t now_ms, std::uint32_t room = 0,
                       const std::string& room_code = {});
  // Player ids are never reused in the endpoint's life: a newcomer given the id of a
  // player who left was credited with that player's touches (issue 36). From now on no
  // new session gets an id up to `id` (a resumed room's players; restore_session does it
  // for its own). kNoPlayerIdLeft is never given: with it reached, every hello is
  // refused server_full.
  static constexpr std::uint32_t kNoPlayerIdLeft = SessionTable::kNoPlayerIdLeft;
  void reserve_player_ids(std::uint32_t id) { sessions_.reserve_player_ids(id); }
  // One id no newcomer gets, leaving the ids below and above it to this endpoint: a room
  // from another server names ids of that server's range (reserving them would move this
  // server's newcomers into that range, where the other server's next room would find
  // them in use). The set is emptied as the endpoint's own ids pass them.
  void take_player_id(std::uint32_t id) { sessions_.take_player_id(id); }
  // The verifier of a session's token ("" for no such player).
  std::string session_verifier(std::uint32_t player_id) const;
  // Whether a session (connected or held) has this player id.
  bool has_session(std::uint32_t player_id) const { return sessions_.count(player_id) != 0; }
  // The fingerprint of a session's proven identity ("" for a guest or no such player).
  std::string session_identity(std::uint32_t player_id) const;
  // Tells every connected client that the server stops; releases every slot.
  void shutdown(std::uint64_t now_ms);
  // The room went to another server (PROTOCOL.md 4.9b): each of its connected sessions is
  // told where (`moved`, sent three times: it is not acknowledged); every session of the
  // room is released (reason "moved"). Returns how many were told.
  std::size_t move_room(std::uint32_t room, const std::string& address, const std::string& room_code,
                        std::uint64_t now_ms);
  // Rooms are tags the host gives (Admission::room): of each, the endpoint knows what the
  // host tells it, its terms, and forgets them when the room closes (forget_room).
  struct RoomTerms {
    // While a room is paused (the host's lobby, shop and game-over phases) none of its
    // sessions idles: their idle clocks restart when the pause ends.
    bool idle_paused = false;
    // While the room's match runs (the host's playing and shop phases) a player who left
    // it stays the same player when it comes back, whatever the reconnect window: at the
    // window's end its session is kept, as after a quit (no seat, progress kept, its token
    // takes it back while a seat is free), until the match ends (issue 37). At most
    // kMaxKeptPerRoom a room; over it, the window's end releases as before.
    bool keeps_departed = false;
    // The tick reported in welcomes (of a reconnect: the admission gives a new player's).
    std::uint32_t tick = 0;
  };
  static constexpr std::size_t kMaxKeptPerRoom = 32;  // four times a room's 8 seats
  void set_idle_paused(std::uint32_t room, bool paused) {
    serial_only("set_idle_paused");
    rooms_[room].idle_paused = paused;
  }
  void set_keeps_departed(std::uint32_t room, bool keep) {
    serial_only("set_keeps_departed");
    rooms_[room].keeps_departed = keep;
  }
  void set_server_tick(std::uint32_t room, std::uint32_t tick) {
    serial_only("set_server_tick");
    rooms_[room].tick = tick;
  }
  void forget_room(std::uint32_t room) {
    serial_only("forget_room");
    rooms_.erase(room);
  }
  // A room's terms (a room never told of: the defaults).
  const RoomTerms& terms(std::uint32_t room) const {
    static const RoomTerms kUntold;
    auto it = rooms_.find(room);
    return it == rooms_.end() ? kUntold : it->second;
  }

  std::vector<Outgoing> take_datagrams();
  // The same for a sender that keeps its batch: `batch` holds the datagrams sent last
  // time, whose buffers are kept for the next ones, and gets the queued ones. In the
  // steady state no datagram allocates (the snapshot path: tests/bench/wire_bench.cpp).
  void take_datagrams(std::vector<Outgoing>& batch);
  std::vector<ServerEvent> take_events();
  std::vector<PlayerInput> take_inputs();
  std::vector<PlayerCommand> take_commands();
  // Sends a chat line (or a host announcement) to one connected player, reliably; false
  // when the player is not connected or its chat queue is full (the line is dropped).
  bool send_chat(std::uint32_t player_id, const Chat& chat, std::uint64_t now_ms);
  std::uint64_t chat_dropped() const { return chat_dropped_; }

  const RejectCounters& rejects() const { return rejects_; }
  std::vector<SessionInfo> sessions() const;
  // One room's sessions (without copying every other room's), and one session's.
  std::vector<SessionInfo> sessions_of_room(std::uint32_t room) const;
  std::optional<SessionInfo> session_info(std::uint32_t player_id) const;
  std::vector<std::uint32_t> connected_players() const;
  // Rooms: connected sessions of a room (players and spectators), seats taken (players
  // not quit, connected or held for a reconnect), connected spectators, every session.
  // Every room's connected sessions (player id order within a room), each room's handed
  // to its snapshot job (server_jobs.hpp). Made again only when a session came, went or
  // was connected or dropped since the last call (SessionTable::generation): valid until then.
  const std::map<std::uint32_t, RoomSessions>& connected_by_room();
  std::vector<std::uint32_t> connected_in_room(std::uint32_t room) const;
  std::size_t seats_in_room(std::uint32_t room) const;
  std::size_t spectators_in_room(std::uint32_t room) const;
  std::size_t sessions_in_room(std::uint32_t room) const;
  // Sessions of a room that hold something: connected, or a player who played (its
  // progress waits for the reconnect window). A room with none holds nobody: a host
  // may close it at once (one that only shook hands and left, issue 36).
  std::size_t holding_in_room(std::uint32_t room) const;
  // Time the server itself stood still (gaps over stall_threshold_ms), in total.
  std::uint64_t stalled_ms() const { return stalled_ms_; }

  // ---- Phases (issue 39). While a pool's jobs run, they touch only what they were
  // handed (server_jobs.hpp) and the endpoint takes const reads only (not the per-room
  // counts, whose index is made on their first read); every mutator
  // checks that no parallel phase is on. The host holds a
  // ParallelPhase for each pool run. Checked where FTS_PHASE_CHECKS is defined (the
  // sanitized and ThreadSanitizer builds: kPhaseChecks): a call out of phase throws
  // std::logic_error naming it (a pool rethrows it on its caller).
  class ParallelPhase {
   public:
    explicit ParallelPhase(ServerEndpoint& e) : e_(e) { e_.parallel_ = true; }
    ~ParallelPhase() { e_.parallel_ = false; }
    ParallelPhase(const ParallelPhase&) = delete;
    ParallelPhase& operator=(const ParallelPhase&) = delete;

   private:
    ServerEndpoint& e_;
  };
#ifdef FTS_PHASE_CHECKS
  static constexpr bool kPhaseChecks = true;
#else
  static constexpr bool kPhaseChecks = false;
#endif

 private:
  bool parallel_ = false;  // a pool's jobs run (ParallelPhase)
  void serial_only(const char* call) const {
    if (kPhaseChecks && parallel_)
      throw std::logic_error(std::string("ServerEndpoint::") + call + " called while a pool's jobs run on the endpoint");
  }
  using Session = ServerSession;  // server_session.hpp: one client's session

  void overflow(Session& s, const std::string& what, std::uint64_t now_ms);
  void handle_hello(const Address& from, const Header& header, const Hello& hello,
                    std::size_t request_bytes, std::uint64_t now_ms);
  // receive()'s checks before the crypto: the session a sealed datagram is for, or
  // nullptr when the datagram was dealt with (dropped and counted, or a handshake).
  Session* screen(const Address& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms);
  // Its first half, the checks of the sender (its host's rate, the header, the version; a
  // handshake handled here): the session id a sealed datagram names, or 0 when dealt with.
  // receive_later() makes only these; the InboxJob asks session_for.
  std::uint32_t screen_sender(const Address& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms);
  // What applying a datagram of session `session_id` left for everyone (its inputs and
  // commands queued for the game; the session ended by a bye or an overflow), taken in
  // arrival order. The shared half of applying a datagram; ServerSession::apply did the rest.
  void settle(std::uint32_t player_id, std::uint32_t session_id, Applied& applied, std::uint64_t now_ms);
  // The session `player_id` if it is still the connected session `session_id`.
  Session* live_session(std::uint32_t player_id, std::uint32_t session_id);
  void reply_unconnected(const Address& to, Encoding encoding, std::uint32_t session,
                         const Message& message, std::size_t request_bytes);
  void send_welcome(Session& s, bool reconnected, std::size_t request_bytes, std::uint64_t now_ms);
  void start_session(Session& s, const Address& from, Encoding encoding, const Hello& hello,
                     const SessionKeys& keys, std::uint64_t now_ms);
  // After the handshake's proofs: a player taken back, or a new one admitted; or why not.
  std::variant<Session*, HelloAnswer> take_back(Session* back, const Address& from, Encoding enc, const Hello& hello,
                                                const ProvenHello& proven, std::uint64_t now_ms);
  std::variant<Session*, HelloAnswer> admit_new(const Address& from, Encoding enc, const Hello& hello,
                                                const ProvenHello& proven, std::uint64_t now_ms);
  std::size_t sessions_from(std::string_view host, bool spectators) const;
  void observe_time(std::uint64_t now_ms);
  void send_packet(Session& s, std::vector<Message> messages, bool with_results, std::uint64_t now_ms);
  // by_room_ and held_ made again if a session came, went, connected or dropped since.
  void refresh_rooms();
  // Every session of a room (connected or not, in player id order): the per-room counts
  // read their room's sessions, not the whole table (a quick-play hello asks for the seats
  // of every open room). Made again on the first read after a session came, went,
  // connected or dropped (a session's room never changes otherwise); flags are read live.
  const std::vector<const Session*>& members_of(std::uint32_t room) const;
  // A session's next header (its sequence and acks stamped).
  Header session_header(Session& s, std::uint64_t now_ms);
  void drop_connection(Session& s, const std::string& reason, std::uint64_t now_ms);
  void release(std::uint32_t player_id, const std::string& reason);
  void emit(const Address& to, std::vector<std::uint8_t> bytes);

  ServerConfig config_;
  Handshake handshake_;  // what a hello must prove (handshake.hpp)
  std::vector<std::uint8_t> plain_;  // scratch: the payload of the datagram being opened
  Applied applied_;  // scratch: what receive() applied
  SessionTable sessions_;  // by player id, address and session id; the player ids (server_session.hpp)
  AddressLimits limits_;  // the per-host limits: the one part the sessions of a host share
  std::uint64_t last_forget_ms_ = 0;
  std::unordered_map<std::uint32_t, RoomTerms> rooms_;  // each room's terms, as the host set them
  std::uint64_t sessions_made_ = 0;
  std::uint64_t last_call_ms_ = 0;
  std::uint64_t stalled_ms_ = 0;
  // The endpoint's own lane: the queue every datagram goes out by (rooms' lanes are
  // adopted into it), sent datagrams kept for their buffers (at most kSpareDatagrams:
  // beyond, freed) and the scratch of the payload being sealed.
  static constexpr std::size_t kSpareDatagrams = 4096;
  SendLane lane_;
  // The first inbox_used_ are this tick's (a deque: a job holds its datagrams' addresses
  // while more are queued).
  std::deque<InboxDatagram> inbox_;
  std::size_t inbox_used_ = 0;
  // One per SessionShard, its datagrams this tick's; never resized (inbox_queued_ points in).
  std::vector<InboxJob> inbox_jobs_ = std::vector<InboxJob>(SessionShard::kShards);
  std::vector<InboxJob*> inbox_queued_;    // those with datagrams, in the order they got their first
  std::map<std::uint32_t, RoomSessions> by_room_;  // connected_by_room(), as of by_room_generation_
  std::vector<Session*> held_;  // the sessions not connected, as of by_room_generation_
  std::uint64_t by_room_generation_ = ~std::uint64_t{0};
  std::vector<TimerJob> timer_jobs_;  // the first timer_jobs_used_: one per room in by_room_
  // members_of(), as of members_generation_ (a cache: const reads, on the endpoint's thread only).
  mutable std::unordered_map<std::uint32_t, std::vector<const Session*>> members_;
  mutable std::uint64_t members_generation_ = ~std::uint64_t{0};
  std::size_t timer_jobs_used_ = 0;
  std::vector<ServerEvent> events_;
  std::vector<PlayerInput> inputs_;
  std::vector<PlayerCommand> commands_;
  std::uint64_t chat_dropped_ = 0;
  RejectCounters rejects_;
};

}  // namespace fts::protocol
