// The server without its socket, process part: the one endpoint of the port (sessions,
// limits, rate caps are process-wide), the room table and its lifecycle, and what the
// host's console (app/console_commands.hpp) asks of them. Admission (which room a new
// player gets) is app/admission.cpp; bans are app/bans.hpp. Each room (app/room.hpp) is
// a match of its own; the tick steps the rooms on --threads threads (issue 29) and does
// everything else on the caller's thread, in room-id order. Driven by the time passed
// in, so tests step it by hand.
//
// What the threads share, and how: the endpoint (sessions, queues, limits), the room
// table, codes, chat and the console are touched only by the caller's thread, except in
// the parallel phases of a tick, which change one session's or one room's state per job
// while the caller's thread waits and nothing adds or removes a session. No job is
// handed the endpoint, only what it may change (protocol/server_jobs.hpp):
//   0. receive() makes the cheap checks at once and queues a session's datagram;
//   1. parallel, one job per session (an InboxJob: the session and its datagrams): its
//      queued datagrams opened (replay window, tag, payload) and applied (acks, inputs,
//      commands: ServerSession::apply); then, serial, what they left settled in arrival order;
//   2. parallel, one job per room with connected sessions (a TimerJob: those sessions and
//      a lane): heartbeats and resends sealed, silent and idle sessions listed; then,
//      serial, those ended, reconnect windows, connection events, inputs and commands
//      handed to their rooms;
//   3. parallel, one job per room: Room::step (the match, its record and journal queue);
//   4. serial, room order: results answered, events logged, the room's tick published;
//   5. parallel, one job per room: Room::send_snapshots seals the room's snapshot for
//      its RoomSessions (its connected sessions only) into its own lane;
//   6. serial: the lanes queued in room order.
// The pool's join is the only synchronisation on the tick path (no lock per room or per
// datagram), and everything leaves in the same order for any thread count.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bans.hpp"
#include "app/chat_relay.hpp"
#include "app/log.hpp"
#include "app/options.hpp"
#include "app/profile_requests.hpp"
#include "app/room.hpp"
#include "app/room_codes.hpp"
#include "app/stats.hpp"
#include "app/worker_pool.hpp"
#include "fts/protocol/server.hpp"
#include "fts/sim/match.hpp"

namespace fts::server {

// A room that holds nobody (nobody connected, no player's progress kept: its maker
// shook hands and left) is closed this soon rather than after --room-idle-ms: one host
// that made a room and left it every 0.2 s held every room for a minute (issue 36). A
// few seconds, so that a client that lost its first datagrams can still come back.
inline constexpr std::uint64_t kEmptyRoomMs = 3000;

class GameHost {
 public:
  GameHost(const Options& options, const sim::MatchConfig& config, const protocol::ServerKey& key);

  // Records the first room (id 1) into the directory `dir` (--record; Room::record_to).
  void record_to(const std::string& dir, const std::string& version);
  // Records each room into dir/room-<id>/ (--record-dir); with record_to, room 1 goes there.
  void record_dir(const std::string& dir, const std::string& version);

  void receive(const std::string& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms);
  // One tick: connection events, inputs and commands to their rooms, every room stepped
  // in id order, empty rooms closed.
  void tick(std::uint64_t now_ms);
  // Tells every client the server stops.
  void shutdown(std::uint64_t now_ms);
  std::vector<protocol::Outgoing> take_datagrams();
  // The same into a batch kept by the sender, whose sent buffers are reused
  // (ServerEndpoint::take_datagrams).
  void take_datagrams(std::vector<protocol::Outgoing>& batch);

  // ---- what the console's commands (app/console_commands.cpp) do
  // Ends a player's session; its client gets error `code` with `message`.
  void kick(std::uint32_t player_id, protocol::ErrorCode code, const std::string& message, std::uint64_t now_ms);
  // Kicks the room's clients with `code` and `message`, finishes its journal and record.
  void close_room(std::uint32_t id, protocol::ErrorCode code, const std::string& message, std::uint64_t now_ms);
  // A chat line from the host to every connected client; how many were told.
  std::size_t announce(const std::string& text, std::uint64_t now_ms);
  // The console's drain: no new rooms from now on (see drained()).
  void stop_new_rooms();
  Bans& bans() { return bans_; }
  const Bans& bans() const { return bans_; }
  const Options& options() const { return options_; }
  // drain was asked and the last room has closed: the process should exit 0.
  bool drained() const { return draining_ && rooms_.empty(); }
  // The fleet's drain (SIGTERM under Agones): no new rooms, and a new player is refused
  // with "draining"; reconnects still resume. The console's drain only stops new rooms.
  void set_draining(bool draining) { draining_ = refuse_players_ = draining; }
  bool draining() const { return draining_; }

  // ---- crash-safe journal (issue 15; app/game_host_journal.cpp). With journal_rooms(),
  // every room journals into base.dir/<room code>/ from its opening on (base gives the
  // sync, checkpoint and queue settings); a room that closes finishes its journal (the
  // directory goes, on the writer's thread: the tick never waits for the disk).
  void journal_rooms(store::JournalConfig base);
  // Opens a room rebuilt from its journal (store::read_journal): its code, id (a fresh one
  // if that id is taken), privacy, seed, match and event numbering; its sessions come back
  // away until their clients return with their tokens. False (logged): the code is not a
  // room code or is taken, or the server has max_rooms rooms.
  // `foreign`: a room handed over by another server (adopt_room): its player ids are that
  // server's, each taken here without moving this server's own ids on (take_player_id).
  bool resume_room(const store::ResumedRoom& room, std::uint64_t now_ms, bool foreign = false);
  const store::JournalWriter* journal(std::uint32_t room_id) const;
  store::JournalWriter* journal(std::uint32_t room_id);
  // ---- rooms that move (issue 42; app/game_host_handover.cpp, PROTOCOL.md 4.9b). A room
  // handed over is frozen (it steps no more) while its journal, flushed to its tick, goes
  // to the peer; then either the peer took it (room_moved: its clients are told where, and
  // it closes here without a result: the match goes on there) or not (room_kept: it plays
  // on here). The peer's side is adopt_room.
  struct RoomExport {
    std::string code;
    std::int64_t tick = 0;
    std::vector<std::pair<std::string, std::string>> files;  // the journal's segments: name, text
  };
  // Each room named, frozen with its export, or why not (it plays on); their journals
  // sync together.
  std::vector<std::variant<RoomExport, std::string>> export_rooms(const std::vector<std::string>& codes);
  std::size_t room_moved(const std::string& code, const std::string& address, std::uint64_t now_ms);
  void room_kept(const std::string& code, const std::string& why);
  // A room from a peer: its journal's segments. "" when it plays here now (at the tick it
  // left), else why not (nothing changed).
  std::string adopt_room(const std::string& code, const std::vector<std::pair<std::string, std::string>>& files,
                         std::uint64_t now_ms);
  // A room adopted is held unconfirmed until the sender confirms it (PROTOCOL.md 14, step
  // 4) or one of its clients arrives here (the sender told them where: it had confirmed).
  // One confirmed neither way within kUnconfirmedMs is forgotten: closed without a result,
  // its journal removed, because the sender kept it (its answer or the confirmation was
  // lost) and a second copy must not live on here. Meanwhile its journal's directory holds
  // the file JournalRoot::kUnconfirmedMark, so that a server restarted with --resume holds
  // it again. The sender's side: room_moved first marks the room's journal directory with
  // JournalRoot::kMovedMark (room_journals.hpp).
  static constexpr std::uint64_t kUnconfirmedMs = 10'000;
  // `by`: "sender" or "client" (logged). False when no such room is held unconfirmed.
  bool confirm_adopted(const std::string& code, const char* by);
  bool unconfirmed(const std::string& code) const;
  std::uint64_t rooms_forgotten() const { return rooms_forgotten_; }
  // Writers of closed rooms still finishing (removed each tick once stopped).
  std::size_t closing_journals() const { return closing_journals_.size(); }
  // The wire events of one step, as the room stepper numbers them (benchmarks that write
  // journals by hand).
  static std::uint32_t wire_event_count(std::int64_t tick, const sim::TickOutput& out);

  // The first room's match (an empty lobby when there is no room): single-room tests.
  const sim::MatchState& match() const;
  // The input frames' timing summed over the open rooms (PROTOCOL.md 4.5).
  InputTiming input_timing() const;
  const Room* room(std::uint32_t id) const;
  const Room* room_by_code(const std::string& code) const;
  std::vector<std::uint32_t> room_ids() const;
  std::uint64_t rooms_made() const { return rooms_made_; }
  // Hand-overs (issue 42): rooms this server gave to a peer, took from one, and kept
  // because the peer refused or could not be reached.
  std::uint64_t rooms_moved() const { return rooms_moved_; }
  std::uint64_t rooms_adopted() const { return rooms_adopted_; }
  std::uint64_t handovers_refused() const { return handovers_refused_; }
  // The rooms' journals as last seen (each room looks once a second).
  struct JournalHealth {
    std::size_t rooms = 0;       // journaled rooms
    std::size_t failing = 0;     // of them, not journaling for an I/O error (retrying)
    std::uint64_t failures = 0;  // times a journal stopped (closed rooms too)
    std::string error;           // the first failing room's code and error
  };
  JournalHealth journal_health() const;
  const protocol::ServerEndpoint& endpoint() const { return endpoint_; }
  const WorkerPool& workers() const { return pool_; }
  Stats& stats() { return stats_; }

  // ---- profiles (issue 41): with a writer, each room follows its players with an
  // identity and hands their results to it; a player with an identity is "seen" when it
  // connects. `unix_s` is the wall clock (tests give their own: "a day later").
  void use_profiles(profiles::Writer* writer, std::function<std::int64_t()> unix_s);
  profiles::Writer* profiles() const { return profiles_; }

 private:
  struct Member {
    std::uint32_t room = 0;
    bool spectator = false;
  };
  protocol::Admission admit(const protocol::JoinAsk& ask);
  Room* create_room(bool is_private, const std::string& maker_host);
  // Closes the room that holds nobody (ServerEndpoint::holding_in_room) and has been
  // empty the longest (the lowest id among equals), one `maker` made if given; whether
  // there was one. A new room never waits for --room-idle-ms while such a room is open.
  bool reclaim_room(const std::string* maker, std::uint64_t now_ms);
  std::size_t rooms_made_by(const std::string& host) const;
  Room* open_room(std::uint32_t id, const std::string& code, bool is_private, std::uint64_t seed,
                  const sim::MatchConfig& config);
  // A room leaves the host (closed, or moved to a peer): its journal finishes, its record
  // is sealed, its entries go.
  void retire_room(std::map<std::uint32_t, std::unique_ptr<Room>>::iterator it);
  // Unconfirmed adopted rooms past their time are forgotten (each tick).
  void forget_unconfirmed(std::uint64_t now_ms);
  std::map<std::uint32_t, std::unique_ptr<Room>>::iterator room_at(const std::string& code);  // or end()
  void start_journal(Room& r);
  void finish_journal(Room& r);
  bool journal_exists(const std::string& code) const;  // a directory of that code under the root
  void dispatch(std::uint64_t now_ms);
  void answer_rooms(const protocol::PlayerCommand& pc, std::uint64_t now_ms);
  // `cmd top` and `cmd forget` (PROTOCOL.md 4.7c): asked of the profile writer's thread;
  // answered when it has answered (answer_profiles, each tick).
  void profile_request(const protocol::PlayerCommand& pc, std::uint64_t now_ms);
  void answer_profiles(std::uint64_t now_ms);
  // A chat command: refused, or relayed to everybody connected in the sender's room.
  void relay_chat(const protocol::PlayerCommand& pc, std::uint64_t now_ms);
  std::string room_list_text() const;

  Options options_;
  sim::MatchConfig config_;
  protocol::ServerEndpoint endpoint_;
  std::map<std::uint32_t, std::unique_ptr<Room>> rooms_;  // by id: the stepping order
  std::uint64_t closed_journal_failures_ = 0;
  std::map<std::uint32_t, Member> members_;               // by player id
  RoomCodes codes_;
  std::uint32_t next_room_id_ = 1;
  std::uint64_t rooms_made_ = 0;
  std::uint64_t rooms_moved_ = 0, rooms_adopted_ = 0, handovers_refused_ = 0, rooms_forgotten_ = 0;
  std::uint64_t now_ms_ = 0;  // the time last passed in (admit() is called without it)
  bool draining_ = false;
  bool refuse_players_ = false;
  ChatRelay chat_;
  std::optional<store::JournalConfig> journal_base_;  // journal_rooms(): dir is the root
  std::vector<std::unique_ptr<store::JournalWriter>> closing_journals_;
  Bans bans_;
  std::string first_record_;  // --record: room 1's record directory
  std::string record_dir_;
  std::string version_;
  std::uint64_t stalled_logged_ms_ = 0;
  sim::MatchState no_match_;
  Stats stats_;
  profiles::Writer* profiles_ = nullptr;
  std::function<std::int64_t()> unix_s_;
  ProfileRequests profile_requests_;
  WorkerPool pool_;
  // Each pool thread's scratch for opening the inbox (by slot: the pool owns the threads,
  // the host the buffers they reuse).
  std::vector<std::vector<std::uint8_t>> open_scratch_;
  std::vector<Room*> order_;                // this tick's rooms in id order (phases 3-6)
  std::vector<protocol::SendLane> lanes_;   // one per position in order_
};

protocol::ServerConfig make_endpoint_config(const Options& options, const sim::MatchConfig& config,
                                            const protocol::ServerKey& key);

// The seed of room `id`: the server's seed for room 1 (a one-room server plays as before
// rooms), a mix of it and the id for the others.
std::uint64_t room_seed(std::uint64_t server_seed, std::uint32_t room_id);

}  // namespace fts::server
