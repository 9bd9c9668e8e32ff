// A player's own requests about profiles (issue 41, PROTOCOL.md 4.7c): `cmd top` (the
// leaderboard and the player's rank) and `cmd forget` (erase the profile of the
// session's identity). The tick never waits for the database: each request is a job on
// the profile writer's thread (profiles::Writer::query), whose answer comes back through
// a mailbox the tick empties at its next run. One request per player at a time, and at
// most one a second (kMinIntervalMs: a client that asks in a loop keeps the database
// thread no busier than that); an answer for a session that has gone since (a reconnect
// starts its rids again) is dropped.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "fts/protocol/codes.hpp"
#include "fts/protocol/messages.hpp"
#include "profiles/store.hpp"
#include "profiles/writer.hpp"

namespace fts::server {

// A name from the profile database as a board row holds it (PROTOCOL.md 4.7c): cleaned
// as a chat line is (printable ASCII, each UTF-8 sequence or other byte one '?'), cut to
// 16, "?" when nothing is left. The database may be shared and older than this server.
std::string board_name(const std::string& raw);

// The top rows and the count of ranked players, read again only when the writer has
// committed something since (generation: WriterStats::committed).
struct BoardCache {
  bool valid = false;
  std::uint64_t generation = 0;
  std::vector<protocol::BoardRow> top;
  std::uint32_t of = 0;
};

// The board for `fingerprint` ("" a guest): the cache's rows (read first if stale) and
// the player's rank, best level and its coins. Throws what the store throws.
protocol::Leaderboard read_board(profiles::Store& store, BoardCache& cache, std::uint64_t generation,
                                 const std::string& fingerprint);

struct ProfileAnswer {
  std::uint32_t player = 0;
  std::uint32_t rid = 0;      // the command answered
  std::uint64_t serial = 0;   // which request (ProfileRequests' own count)
  protocol::ResultCode code = protocol::ResultCode::ok;
  std::string message;
  std::optional<protocol::Leaderboard> board;
};

class ProfileRequests {
 public:
  ProfileRequests();
  static constexpr std::uint64_t kMinIntervalMs = 1000;
  // May the player ask now (none of its requests unanswered, none in the last second)?
  // Counts the ask when it may.
  bool may_ask(std::uint32_t player, std::uint64_t now_ms);
  // Asks the writer for the board of `fingerprint` ("" a guest) for the player's command.
  void top(profiles::Writer& writer, std::uint32_t player, std::uint32_t rid, const std::string& fingerprint);
  // Queues the erasure of `fingerprint`'s profile and asks for its outcome. False: the
  // writer's queue is full (nothing queued; answer `unavailable`).
  bool forget(profiles::Writer& writer, std::uint32_t player, std::uint32_t rid, const std::string& fingerprint);
  // The player's session is new or gone: an answer still to come for it is dropped.
  void drop(std::uint32_t player) {
    in_flight_.erase(player);
    last_ask_ms_.erase(player);
  }
  // The answers that came, for requests still waited for (tick thread).
  std::vector<ProfileAnswer> take();

 private:
  struct Shared {
    std::mutex mu;
    std::vector<ProfileAnswer> answers;  // under mu
    BoardCache cache;                    // the writer's thread only
  };
  std::uint64_t begin(std::uint32_t player, std::uint32_t rid);
  std::shared_ptr<Shared> shared_;
  struct InFlight {
    std::uint32_t rid = 0;
    std::uint64_t serial = 0;
  };
  std::map<std::uint32_t, InFlight> in_flight_;  // by player (tick thread)
  std::map<std::uint32_t, std::uint64_t> last_ask_ms_;
  std::uint64_t serial_ = 0;
};

}  // namespace fts::server
