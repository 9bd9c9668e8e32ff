// The journal directory of a server (--journal-dir DIR, issue 15): DIR/lock (one server
// at a time), DIR/<room code>/ per room (store/journal.hpp), DIR/<code>.closed/ while a
// closed room's journal is being removed. --resume reads every room's journal, rooms in
// parallel (each room's replay alone is deterministic), before the port opens.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "app/game_host.hpp"
#include "store/journal.hpp"

namespace fts::server {

// Holds DIR/lock (flock) for the process's life: a second server on the same directory
// would interleave the rooms' segments.
class JournalRoot {
 public:
  // Makes the directory if missing, takes the lock and removes leftovers of finished
  // journals (<code>.closed) and of rooms handed over to a peer (a directory holding
  // kMovedMark: the server stopped before its writer removed it). error() says why not
  // (nothing else done then).
  explicit JournalRoot(std::filesystem::path dir);
  ~JournalRoot();
  JournalRoot(const JournalRoot&) = delete;
  JournalRoot& operator=(const JournalRoot&) = delete;
  const std::string& error() const { return error_; }
  const std::filesystem::path& dir() const { return dir_; }
  // The room journals in it: subdirectories named as room codes, in code order.
  std::vector<std::string> room_codes() const;

  // The marks a room's directory may hold (rooms that move, PROTOCOL.md 14). A room handed
  // to a peer: GameHost::room_moved writes kMovedMark first (the journal's writer removes
  // the directory later, on its own thread), so that a server stopped in between does not
  // resume a room that now plays at the peer (this constructor removes it). A room adopted
  // from a peer and not yet confirmed: kUnconfirmedMark, so that a server restarted with
  // --resume holds it unconfirmed again (GameHost::kUnconfirmedMs).
  static constexpr const char* kMovedMark = "moved";
  static constexpr const char* kUnconfirmedMark = "unconfirmed";

 private:
  std::filesystem::path dir_;
  int lock_fd_ = -1;
  std::string error_;
};

struct RoomJournalRead {
  std::string code;  // the directory's name
  std::variant<store::ResumedRoom, std::string> result;
  double ms = 0;  // this room's read and replay
};

// Every room journal of `codes` under `dir` read with store::read_journal (the host's
// event numbering), on up to `threads` threads; results in the order of `codes`.
std::vector<RoomJournalRead> read_room_journals(const std::filesystem::path& dir, const std::vector<std::string>& codes,
                                                unsigned threads);

struct ResumeSummary {
  std::size_t rooms = 0;    // journals found
  std::size_t resumed = 0;  // rooms open again
  std::size_t skipped = 0;  // reported, left on disk
  std::size_t sessions = 0;
};

// The match config the resumed rooms share: the lowest room id's (nullopt: none read).
std::optional<sim::MatchConfig> resumed_config(const std::vector<RoomJournalRead>& reads);

// Opens each room read well in `host`, logging each one (resumed, its damage and skipped
// segments) and each one skipped with the reason: nothing usable, not a room code, or a
// match config other than `config` (one server runs one config).
ResumeSummary resume_rooms(GameHost& host, const std::vector<RoomJournalRead>& reads, const sim::MatchConfig& config,
                           std::uint64_t now_ms);

}  // namespace fts::server
