// A room's journal: what a restarted server needs to resume the room where it stood.
// It is the match record (server/store/record.hpp: seed, config, input lines, hashes)
// cut into segments that each begin with a checkpoint (the whole MatchState and its hash),
// plus what the inputs do not carry: the sessions (player id, name, a verifier of the
// reconnect token, never the token) and the event sequence number.
//
// One directory per room (the host names it after the room's code: DIR/ABCDE/), one file
// per segment, one JSON object per line:
//   journal-000001.jsonl
//   {"fts_journal":1,"version":"0.1.0","room":"ABCDE","room_id":3,"private":false,"segment":1,"seed":7,"config":{...}}
//   {"tick":0,"checkpoint":{...MatchState...},"hash":"9c3e...","event_seq":0,"sessions":[...]}
//   {"tick":0,"session":{"player":1,"name":"ann","verifier":"5d1f...","quit":false}}
//   {"tick":0,"joins":[{"player":1,"name":"ann"}]}          <- an input line (record.hpp)
//   {"tick":10,"hash":"41aa...","event_seq":3}              <- after 10 ticks were stepped
//   {"tick":57,"released":1}
//
// Durability: the tick thread only copies records into a bounded queue; a writer thread
// appends them and calls fdatasync at most every sync_ms, so at most about sync_ms of play
// is lost in a crash. When the queue is full the journal drops records (counted) until it
// has room for a new checkpoint, which starts a new segment: a crash in between resumes
// the room to the last record before the drop. A new segment is a checkpoint; once it is
// durable, segments older than the newest keep_segments are removed, so the disk holds
// about keep_segments x checkpoint_every_ticks of play per room, whatever the match length.
// A record (keep_all, --record / --record-dir) is the same journal keeping every segment
// and its directory: the room's whole history, which fts-server --replay reads.
// A room that closes finishes its journal (finish()): the directory is renamed to
// <dir>.closed (one atomic step: a crash before it resumes the room, after it does not)
// and removed.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "fts/room/record.hpp"
#include "fts/sim/match.hpp"

namespace fts::store {

// The format, the segments' names and their listing are the history reader's (fts_room),
// which reads a journal that keeps every segment as a whole match.
using room::kJournalFormat;
using room::list_segments;
using room::segment_name;

struct JournalSession {
  std::uint32_t player = 0;
  std::string name;
  std::string verifier;  // protocol::token_verifier(token)
  bool quit = false;     // gave its seat up (bye or idle), progress kept
  std::string identity = "";  // its proven identity's fingerprint ("" a guest; PROTOCOL.md 5.8)
  std::string career = "";    // its match so far (app/careers.hpp Careers::saved; "" none)
  bool operator==(const JournalSession&) const = default;
};

struct JournalConfig {
  std::filesystem::path dir;  // this room's directory (made if missing)
  std::string room = "main";  // the room's code
  std::uint32_t room_id = 0;  // the host's id of the room (0: none)
  bool is_private = false;    // made with "create" (not offered to quick play)
  std::string version;
  std::uint64_t seed = 0;
  std::uint32_t sync_ms = 100;                  // fdatasync at most this often
  std::int64_t checkpoint_every_ticks = 1000;   // a new segment (10 s at 100 Hz)
  std::int64_t hash_every_ticks = 10;           // a hash line (also the resume's rollback points)
  std::size_t max_queued = 16384;               // records waiting for the writer; full: dropped
  std::size_t keep_segments = 2;                // >= 1
  bool keep_all = false;  // a record: every segment kept, and the directory when the room closes
};

struct JournalStats {
  std::uint64_t records = 0;           // written
  std::uint64_t bytes = 0;             // written
  std::uint64_t syncs = 0;
  std::uint64_t segments = 0;          // started by this writer
  std::uint64_t removed_segments = 0;
  std::uint64_t dropped = 0;           // records dropped for a full queue
  std::int64_t durable_tick = -1;      // the newest tick whose records are durable
  // An I/O error (disk full, read-only, gone) stops the journal, not the room: records are
  // discarded while it fails, and once a second a new segment starting with a checkpoint
  // is tried; when that one is durable, journaling goes on from it (recoveries).
  std::string error;                   // while failing: the I/O error; or the directory's lock error (for good)
  bool failing = false;                // journaling stopped on an I/O error; retrying
  std::uint64_t failures = 0;          // times it stopped on an I/O error
  std::uint64_t recoveries = 0;        // times a retry's checkpoint was durable again
  std::uint64_t discarded = 0;         // records not written because it was failing
  bool finished = false;               // finish(): the room's directory is removed
};

// The writer. The tick thread calls inputs() before step() and stepped() after it;
// neither blocks on the disk.
class JournalWriter {
 public:
  // Starts a new segment (after the newest one in cfg.dir) with a checkpoint of `state`.
  // When the directory is locked by another writer, stats().error says so and nothing
  // is ever written.
  JournalWriter(JournalConfig cfg, const sim::MatchConfig& match_config, const sim::MatchState& state,
                std::uint32_t event_seq, std::vector<JournalSession> sessions);
  ~JournalWriter();  // writes and syncs what is queued, then stops
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;

  void inputs(std::int64_t tick, const sim::TickInputs& in);
  void session(std::int64_t tick, const JournalSession& s);
  void released(std::int64_t tick, std::uint32_t player);
  // After a step: the hash line when due, the checkpoint (a new segment) when due.
  void stepped(const sim::MatchState& state, std::uint32_t event_seq);
  // A hash line of the state now, whatever its tick, unless one was written for it (a room
  // that closes ends its record with it, so a replay ends on the hash the room ended on).
  void hash_now(const sim::MatchState& state, std::uint32_t event_seq);
  // A checkpoint of the state now, which starts a new segment (a room handed to a peer
  // ships that segment alone: the peer replays nothing). Skipped while the journal drops
  // records or fails (stats() says so).
  void checkpoint_now(const sim::MatchState& state, std::uint32_t event_seq) { checkpoint(state, event_seq); }
  // Blocks until everything queued so far is written and synced (tests, shutdown).
  void flush();
  // Asks the writer to sync what is queued now, without waiting (a later flush() waits
  // for it): rooms handed over together sync at once, each on its writer's thread.
  void request_flush();
  // The room closed: nothing more is journaled; the writer thread writes what is queued,
  // then removes the room's directory (rename to <dir>.closed, then delete) and stops.
  // Returns at once; stopped() says when it is done (the destructor waits for it).
  void finish();
  bool stopped() const;
  JournalStats stats() const;

  static constexpr std::chrono::milliseconds kRetryEvery{1000};  // a failed journal's next try

 private:
  struct Inputs {
    std::int64_t tick;
    sim::TickInputs in;
  };
  struct Hash {
    std::int64_t tick;
    std::uint64_t hash;
    std::uint32_t event_seq;
  };
  struct Session {
    std::int64_t tick;
    JournalSession s;
  };
  struct Released {
    std::int64_t tick;
    std::uint32_t player;
  };
  struct Checkpoint {
    sim::MatchState state;
    std::uint32_t event_seq;
    std::vector<JournalSession> sessions;
  };
  // A checkpoint is held by pointer: records stay small, so the queue's nodes are cheap.
  using Record = std::variant<Inputs, Hash, Session, Released, std::unique_ptr<Checkpoint>>;

  void push(Record r);
  void checkpoint(const sim::MatchState& state, std::uint32_t event_seq);
  void run();
  std::int64_t write_batch(std::deque<Record>& batch);  // the newest tick written
  bool open_segment();
  void remove_old_segments();
  void remove_journal();
  void fail(const std::string& what);
  void stop_failing(std::deque<Record>& rest);  // the writer: discards a failed batch's rest

  JournalConfig cfg_;
  std::string header_config_;  // the MatchConfig as JSON, written in every header
  // Tick thread.
  std::map<std::uint32_t, JournalSession> sessions_;
  std::int64_t next_checkpoint_tick_ = 0;
  std::int64_t last_hash_tick_ = -1;  // the tick of the newest hash line or checkpoint
  bool dropping_ = false;  // the queue overflowed: nothing is queued until the next checkpoint
  // Shared.
  mutable std::mutex mu_;
  std::condition_variable wake_;
  std::condition_variable done_;
  std::deque<Record> queue_;
  bool stop_ = false;
  bool flush_requested_ = false;
  bool finish_ = false;   // finish() was called
  bool exited_ = false;   // the writer thread is done (or never ran)
  bool writer_idle_ = false;      // the writer waits for a first record (push wakes it)  // flush() waits: sync without waiting for sync_ms
  bool retry_queued_ = false;     // failing: a checkpoint to start again is queued
  std::chrono::steady_clock::time_point retry_at_{};  // failing: no new try before this
  std::uint64_t pushed_ = 0;    // records queued so far
  std::uint64_t synced_ = 0;    // records durable so far
  JournalStats stats_;
  // Writer thread.
  int fd_ = -1;
  int lock_fd_ = -1;  // flock on <dir>/lock for the writer's life
  std::uint64_t segment_ = 0;
  std::thread thread_;
};

// ----- reading (store/journal_read.cpp) -----------------------------------------------------------------------

struct ResumedRoom {
  std::string room;  // the room's code
  std::uint32_t room_id = 0;
  bool is_private = false;
  std::string version;
  std::uint64_t seed = 0;
  sim::MatchConfig config;
  sim::MatchState state;  // at the last good tick
  std::uint32_t event_seq = 0;
  std::vector<JournalSession> sessions;  // by player id
  std::uint64_t segment = 0;             // the segment resumed from
  std::int64_t checkpoint_tick = 0;
  std::int64_t ticks_replayed = 0;
  std::int64_t hashes_checked = 0;
  std::string damage;                 // "": the segment read to its end; else where and why it stopped
  std::vector<std::string> skipped;   // newer segments that could not be used, and why
};

// Rebuilds a room from the newest segment whose header and checkpoint are good: the
// checkpoint (its hash checked), then every later line, each hash line checked. A torn or
// unreadable line ends the replay there; a hash that differs rolls back to the last hash
// that matched. Either way `damage` says so. Only when no segment is usable: a message.
// The ticks are stepped by the room stepper (fts_room), as the server's rooms step them,
// so the resumed event numbering is the crashed server's (checked at each hash line).
std::variant<ResumedRoom, std::string> read_journal(const std::filesystem::path& room_dir);

}  // namespace fts::store
