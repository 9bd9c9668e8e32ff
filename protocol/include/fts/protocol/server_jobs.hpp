// What a job on the host's worker pool is handed (issue 39): one session's datagrams to
// open, or one room's connected sessions to send a snapshot to, and the lane it seals
// into; never the endpoint. Two jobs hold disjoint sessions, so the types, not a comment,
// keep them apart. The endpoint makes them in its serial part (ServerEndpoint::inbox_jobs,
// connected_by_room); they stay valid until the endpoint is next called (no session comes
// or goes while the jobs run).
#pragma once

#include <cstdint>
#include <optional>
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
};

// A datagram of a session waiting in the endpoint's inbox (ServerEndpoint::receive_later).
struct InboxDatagram {
  std::uint32_t player_id = 0, session_id = 0;
  std::uint64_t now_ms = 0;
  std::vector<std::uint8_t> bytes;  // kept for the next datagram's copy
  std::optional<Decoded<Datagram>> opened;
};

// One session's datagrams of this tick, to open (replay window, tag, payload) with its
// seal. A session gone since they came has no seal: its datagrams stay unopened and are
// counted as such when applied (unknown_session).
class InboxJob {
 public:
  // In arrival order; `scratch` is the calling thread's buffer (the pool keeps one per
  // thread).
  void open(std::vector<std::uint8_t>& scratch);

 private:
  friend class ServerEndpoint;
  SealedChannel* seal_ = nullptr;
  std::uint32_t session_id_ = 0;  // the session's now: datagrams of an older one stay unopened
  std::uint16_t version_ = 0;
  std::vector<InboxDatagram*> datagrams_;
};

// Seals `quantized` for `s` (a delta against what it acknowledged, in as many parts as it
// takes) into `lane`: touches that session and the lane only.
void seal_snapshot(ServerSession& s, std::uint16_t version, const SharedSnapshot& quantized, std::uint64_t now_ms,
                   SendLane& lane);

// A room's connected sessions (players and spectators, in player id order), for the
// room's snapshot job.
class RoomSessions {
 public:
  bool empty() const { return sessions_.empty(); }
  std::size_t size() const { return sessions_.size(); }
  // The snapshot to each of them, sealed into `lane`.
  void send_snapshot(const SharedSnapshot& quantized, std::uint64_t now_ms, SendLane& lane) {
    for (ServerSession* s : sessions_) seal_snapshot(*s, version_, quantized, now_ms, lane);
  }

 private:
  friend class ServerEndpoint;
  std::vector<ServerSession*> sessions_;
  std::uint16_t version_ = 0;
};

}  // namespace fts::protocol
