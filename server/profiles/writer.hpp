// The profile writer (issue 41): the one thread that talks to the profile database, so
// that the tick never waits for it. The tick thread pushes writes (a player seen, a match
// result, a profile forgotten) into a bounded queue; the writer appends them to a durable
// spool file (fdatasync), then writes them to the database in batches (one transaction
// each) and empties the spool once everything in it is in the database.
//
// When the database is down or slow the game goes on: writes wait in the spool (and in
// memory, up to kMaxPending), the writer tries to connect again every retry_ms, and
// writes them once it is back. A crash loses nothing either: the next fts-server with the
// same spool directory adopts every spool file no live process holds (each is held with
// flock) and writes it. Results are idempotent by their key (Store::write), so one that
// was in the database and in a spool counts once.
//
// Queries (the console's top and profile, a client's leaderboard or forget) are jobs run
// on the same thread between batches; their answers go back through the callback they
// carry (on the writer's thread: the caller posts them to its own). A query runs after
// every write pushed before it was asked has been tried: with the database up, it sees
// them written.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "profiles/store.hpp"

namespace fts::profiles {

struct WriterConfig {
  std::string url;                    // Store::open's
  std::filesystem::path spool_dir;    // where the spool files live (made if missing)
  std::size_t max_queued = 4096;      // writes from the tick not yet taken by the writer; full: dropped (counted)
  std::size_t batch = 2000;           // writes per transaction at most (SQLite: 2000 returning
                                      // players ~12 000/s, 500 ~8 000/s: fts-profile-bench)
  std::uint32_t retry_ms = 1000;      // a failed database is tried again this often
  std::size_t max_queries = 64;       // queries waiting; full: answered at once without a store
};

struct WriterStats {
  std::uint64_t pushed = 0;      // writes accepted from the tick
  std::uint64_t dropped = 0;     // writes refused for a full queue (lost: logged)
  std::uint64_t committed = 0;   // writes in the database (this process)
  std::uint64_t results = 0;     // of them, match results that were new
  std::uint64_t duplicates = 0;  // match results whose key was already written
  std::uint64_t batches = 0;
  std::uint64_t adopted = 0;     // writes read back from spool files at start (a crash)
  std::uint64_t spool_bad_lines = 0;  // spool lines that did not read (a torn last line)
  std::uint64_t failures = 0;    // times the database failed
  std::uint64_t reconnects = 0;  // times it came back
  std::size_t queued = 0;        // in the queue now
  std::size_t pending = 0;       // spooled, waiting for the database
  bool connected = false;        // the last try worked
  std::string error;             // why not (the last failure), "" when connected
  std::string where;             // Store::where()
};

class Writer {
 public:
  // Opens the spool and adopts orphans, then starts the thread, which connects (a
  // database that is down at start is tried again like any failure). `store_error` says
  // what a first Store::open said when it failed for good (a foreign file): the caller
  // checks open_first() before anything else to refuse to start.
  explicit Writer(WriterConfig cfg);
  ~Writer();  // writes what it can (one try), keeps the rest in the spool, stops
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // The spool's error ("" when it works); when it does not, nothing is durable and the
  // server should not start.
  const std::string& spool_error() const { return spool_error_; }

  // The tick's side: never waits for the database or the disk. False: the queue is full,
  // the write is dropped (counted).
  bool push(Write w);
  // A query job, run on the writer's thread with the store (nullptr while the database
  // is unavailable). False: too many waiting; the job is run at once with nullptr.
  bool query(std::function<void(Store*)> job);
  // Waits (tests, benchmarks) until every write pushed so far is in the database; false
  // if they are not after `timeout` (the database is down or slow).
  bool flush(std::chrono::milliseconds timeout = std::chrono::milliseconds(10000));
  WriterStats stats() const;

  // The spool files of a directory (name "spool-*.jsonl").
  static std::vector<std::filesystem::path> spool_files(const std::filesystem::path& dir);

  static constexpr std::size_t kMaxPending = 1'000'000;  // writes kept in memory while the database is away

 private:
  void run();
  bool open_spool();
  void adopt_orphans();
  bool append_spool(const std::vector<Write>& writes);
  void truncate_spool();
  void try_connect();
  void write_pending();
  void run_queries(std::deque<std::function<void(Store*)>>& jobs);

  WriterConfig cfg_;
  std::string spool_error_;
  // Shared with the tick.
  mutable std::mutex mu_;
  std::condition_variable wake_;
  std::condition_variable done_;
  std::deque<Write> queue_;
  std::deque<std::function<void(Store*)>> queries_;
  bool stop_ = false;
  bool flush_waiting_ = false;
  WriterStats stats_;
  // Writer thread.
  std::unique_ptr<Store> store_;
  std::deque<Write> pending_;  // spooled, not yet in the database
  std::chrono::steady_clock::time_point next_try_{};
  int spool_fd_ = -1;
  std::filesystem::path spool_path_;
  std::thread thread_;
};

// A Write as one spool line (JSON) and back; nullopt when the line does not read.
std::string spool_line(const Write& w);
std::optional<Write> read_spool_line(const std::string& line);

}  // namespace fts::profiles
