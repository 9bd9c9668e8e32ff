// What a job on the host's worker pool is handed (issue 39): one shard of the sessions
// and their datagrams to screen and open, or one room's connected sessions to send a
// snapshot to or to keep alive, and the lane it seals into; never the endpoint. Two jobs
// hold disjoint sessions, so the types, not a comment, keep them apart. The endpoint makes
// them in its serial part (ServerEndpoint::inbox_jobs, connected_by_room, timer_jobs); an
// InboxJob stays valid until the endpoint is next called, a TimerJob until settle_timers
// takes what it found, a RoomSessions until a session comes, goes, connects or drops (none
// does while jobs run).
#pragma once

#include <cstdint>
#include <vector>

#include "fts/protocol/codec.hpp"
#include "fts/protocol/seal.hpp"
#include "fts/protocol/server_session.hpp"
#include "fts/protocol/snapshot_delta.hpp"

namespace fts::protocol {

class ServerEndpoint;

// A room's own queue of sealed snapshots (issue 29): rooms on several threads each seal
// into their own lane (its scratch, its queue, the buffers it reuses), and the thread
// that owns the endpoint adopts the lanes in room order, so the datagrams leave in the
// same order whatever the thread count.
struct SendLane {
  std::vector<Outgoing> out;
  std::vector<Outgoing> spare;  // buffers of datagrams sent before, reused
  std::vector<std::uint8_t> payload;
  // A snapshot's encoded parts, one entry per (base, encoding) its sessions needed in one
  // call of RoomSessions::send_snapshot or ServerEndpoint::send_snapshot: the first
  // `encoded_used` (the rest keep their buffers).
  struct Encoded {
    const Snapshot* base = nullptr;
    Encoding encoding = Encoding::msgpack;
    std::size_t parts = 0;
    std::vector<std::vector<std::uint8_t>> payloads;  // the first `parts`
  };
  std::vector<Encoded> encoded;
  std::size_t encoded_used = 0;
};

// A datagram of a session waiting in the endpoint's inbox (ServerEndpoint::receive_later).
struct InboxDatagram {
  std::uint32_t session_id = 0;  // its header's
  std::uint32_t player_id = 0;   // the session's, once a job found it (0: dropped)
  std::uint64_t now_ms = 0;
  Address from;
  std::vector<std::uint8_t> bytes;  // kept for the next datagram's copy
  Applied applied;  // what applying it left for the endpoint (its vectors kept, like bytes)
};

// The datagrams of this tick whose session ids fall in one shard (SessionShard), to
// screen (the session their id names, connected, at their address), open (replay window,
// tag, payload) and apply (ServerSession::apply) on a worker, in arrival order. Touches
// the sessions of its shard, its datagrams and its own reject counts; the endpoint
// settles what they left, serially. Datagrams of a session gone or replaced since they
// came, or after one that ended it, are counted unknown_session.
class InboxJob {
 public:
  // `scratch` is the calling thread's buffer (the pool keeps one per thread).
  void run(std::vector<std::uint8_t>& scratch);
  unsigned shard() const { return sessions_.number(); }

 private:
  friend class ServerEndpoint;
  SessionShard sessions_;
  const ServerConfig* config_ = nullptr;
  RejectCounters rejects_;
  std::vector<InboxDatagram*> datagrams_;
  std::vector<std::uint32_t> ended_;  // sessions a datagram of this run ended (a bye, an overflow)
};

// Seals a datagram of `messages` for `s` into `lane`; `with_results` adds the session's
// results and chat lines that are due (never sent, or unacknowledged for resend_ms); a
// Ping when there is nothing else (a heartbeat). Touches that session and the lane only.
void seal_packet(ServerSession& s, std::uint16_t version, std::vector<Message> messages, bool with_results,
                 std::uint64_t resend_ms, std::uint64_t now_ms, SendLane& lane);

// A room's connected sessions (players and spectators, in player id order), for the
// room's snapshot job and its TimerJob.
class RoomSessions {
 public:
  bool empty() const { return sessions_.empty(); }
  std::size_t size() const { return sessions_.size(); }
  // The snapshot to each of them, sealed into `lane`. Sessions whose deltas have the same
  // base and encoding (most of a room's, when they acknowledge in time) get the same parts:
  // made and encoded once, sealed for each.
  void send_snapshot(const SharedSnapshot& quantized, std::uint64_t now_ms, SendLane& lane) const;
  // A player out of lives who watches its room's match (the room's job says so, each
  // tick) is never dropped for idling: it has nothing to press (issue 37).
  void set_watching(std::uint32_t player_id, bool watching) const {
    for (ServerSession* s : sessions_)
      if (s->player_id == player_id) s->watching = watching;
  }

 private:
  friend class ServerEndpoint;
  friend class TimerJob;
  std::vector<ServerSession*> sessions_;
  std::uint16_t version_ = 0;
};

// One room's connected sessions' timers (ServerEndpoint::timer_jobs): a heartbeat to each
// session sent nothing for heartbeat_ms, its due results and chat lines resent, sealed into
// the job's own lane; a session silent for timeout_ms, or a player without real input for
// idle_timeout_ms (never a spectator or a watcher, nobody while the room is idle-paused),
// listed for the endpoint, which ends them in its serial part (settle_timers). Touches the
// room's sessions and its own lane and lists only.
class TimerJob {
 public:
  void run();

 private:
  friend class ServerEndpoint;
  const RoomSessions* members_ = nullptr;
  const ServerConfig* config_ = nullptr;
  std::uint64_t now_ms_ = 0;
  bool idle_paused_ = false;
  SendLane lane_;  // its buffers kept from tick to tick
  std::vector<ServerSession*> timed_out_, idle_;
};

}  // namespace fts::protocol
