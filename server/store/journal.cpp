#include "store/journal.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

#include <nlohmann/json.hpp>

#include "fts/room/json_fields.hpp"
#include "fts/room/match_config_json.hpp"
#include "store/match_state_json.hpp"
#include "fts/room/text.hpp"

namespace fts::store {

// The JSON helpers and text conversions of the record format live in fts_room.
using namespace fts::room;
namespace {

using Clock = std::chrono::steady_clock;

using ojson = nlohmann::ordered_json;

ojson session_json(const JournalSession& s) {
  ojson j;
  j["player"] = s.player;
  j["name"] = s.name;
  j["verifier"] = s.verifier;
  j["quit"] = s.quit;
  if (!s.identity.empty()) j["identity"] = s.identity;
  if (!s.career.empty()) j["career"] = s.career;
  return j;
}


// Writes all of `text`; false on an error (errno set).
bool write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// A new file's name is durable once its directory is synced.
void sync_dir(const std::filesystem::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

// ----- writer ------------------------------------------------------------------------

JournalWriter::JournalWriter(JournalConfig cfg, const sim::MatchConfig& match_config, const sim::MatchState& state,
                             std::uint32_t event_seq, std::vector<JournalSession> sessions)
    : cfg_(std::move(cfg)), header_config_(match_config_to_json(match_config).dump()) {
  cfg_.keep_segments = std::max<std::size_t>(1, cfg_.keep_segments);
  cfg_.hash_every_ticks = std::max<std::int64_t>(1, cfg_.hash_every_ticks);
  cfg_.checkpoint_every_ticks = std::max<std::int64_t>(1, cfg_.checkpoint_every_ticks);
  for (auto& s : sessions) sessions_[s.player] = std::move(s);
  std::error_code ec;
  std::filesystem::create_directories(cfg_.dir, ec);
  // One writer per room directory: a second server on the same journal would interleave
  // segments. The lock goes with the process (a crash releases it).
  const auto lock_path = cfg_.dir / "lock";
  lock_fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (lock_fd_ < 0 || ::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    stats_.error = "journal: " + cfg_.dir.string() + " is in use by another process (or cannot be locked)";
    stats_.failing = true;  // for good: this writer never writes
    stats_.failures = 1;
    stop_ = exited_ = true;
    return;
  }
  const auto existing = list_segments(cfg_.dir);
  segment_ = existing.empty() ? 0 : existing.back().first;
  checkpoint(state, event_seq);
  thread_ = std::thread([this] { run(); });
}

JournalWriter::~JournalWriter() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (fd_ >= 0) ::close(fd_);
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

void JournalWriter::push(Record r) {
  {
    std::lock_guard lock(mu_);
    if (stop_) return;  // no journal (see the constructor)
    // Failing: records before the retry's checkpoint are covered by it.
    if (stats_.failing && !retry_queued_) {
      ++stats_.discarded;
      return;
    }
    if (dropping_ || queue_.size() >= cfg_.max_queued) {
      dropping_ = true;
      ++stats_.dropped;
      return;
    }
    queue_.push_back(std::move(r));
    ++pushed_;
    // Between syncs the writer sleeps on a timer; waking it for each record would cost
    // the tick a futex call and the machine a context switch per record.
    if (!writer_idle_) return;
  }
  wake_.notify_one();
}

void JournalWriter::checkpoint(const sim::MatchState& state, std::uint32_t event_seq) {
  {
    std::lock_guard lock(mu_);
    if (stop_) return;  // no journal (see the constructor)
    // After a drop, the new segment waits until the writer has caught up by half.
    if (dropping_ && queue_.size() > cfg_.max_queued / 2) return;
    // Failing: one try at a time, at most one a second.
    if (stats_.failing && (retry_queued_ || Clock::now() < retry_at_)) return;
  }
  std::vector<JournalSession> sessions;
  for (const auto& [id, s] : sessions_) sessions.push_back(s);
  auto record = std::make_unique<Checkpoint>(Checkpoint{state, event_seq, std::move(sessions)});
  {
    std::lock_guard lock(mu_);
    if (stop_) return;
    dropping_ = false;
    if (stats_.failing) retry_queued_ = true;
    queue_.push_back(std::move(record));
    ++pushed_;
  }
  next_checkpoint_tick_ = state.tick + cfg_.checkpoint_every_ticks;
  last_hash_tick_ = state.tick;
  wake_.notify_one();
}

void JournalWriter::inputs(std::int64_t tick, const sim::TickInputs& in) {
  if (in.joins.empty() && in.leaves.empty() && in.away.empty() && in.back.empty() && in.quit.empty() &&
      in.players.empty())
    return;
  push(Inputs{tick, in});
}

void JournalWriter::session(std::int64_t tick, const JournalSession& s) {
  sessions_[s.player] = s;
  push(Session{tick, s});
}

void JournalWriter::released(std::int64_t tick, std::uint32_t player) {
  sessions_.erase(player);
  push(Released{tick, player});
}

void JournalWriter::stepped(const sim::MatchState& state, std::uint32_t event_seq) {
  bool again = false;  // dropped records or an I/O error: a new segment as soon as it may start
  {
    std::lock_guard lock(mu_);
    again = dropping_ || stats_.failing;
  }
  if (state.tick >= next_checkpoint_tick_ || again) return checkpoint(state, event_seq);
  if (state.tick % cfg_.hash_every_ticks == 0) hash_now(state, event_seq);
}

void JournalWriter::hash_now(const sim::MatchState& state, std::uint32_t event_seq) {
  if (state.tick == last_hash_tick_) return;
  last_hash_tick_ = state.tick;
  push(Hash{state.tick, sim::match_hash(state), event_seq});
}

void JournalWriter::finish() {
  {
    std::lock_guard lock(mu_);
    if (stop_) return;  // no journal, or finished already
    finish_ = stop_ = true;
  }
  wake_.notify_all();
}

bool JournalWriter::stopped() const {
  std::lock_guard lock(mu_);
  return exited_;
}

void JournalWriter::request_flush() {
  std::lock_guard lock(mu_);
  if (!thread_.joinable()) return;
  flush_requested_ = true;
  wake_.notify_one();
}

void JournalWriter::flush() {
  std::unique_lock lock(mu_);
  if (!thread_.joinable()) return;
  const std::uint64_t target = pushed_;
  flush_requested_ = true;
  wake_.notify_one();
  done_.wait(lock, [&] { return synced_ >= target || !stats_.error.empty(); });
}

JournalStats JournalWriter::stats() const {
  std::lock_guard lock(mu_);
  return stats_;
}

// The writer thread: an I/O error stops journaling (the segment is closed; a segment this
// batch began is removed, so a resume reads the one before) until a retry succeeds.
void JournalWriter::fail(const std::string& what) {
  const int err = errno;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::lock_guard lock(mu_);
  stats_.error = what + ": " + std::strerror(err);
  if (!stats_.failing) ++stats_.failures;
  stats_.failing = true;
  retry_queued_ = false;
  retry_at_ = Clock::now() + kRetryEvery;
}

bool JournalWriter::open_segment() {
  if (fd_ >= 0) {
    ::fdatasync(fd_);  // the old segment's tail is durable before the new one counts
    ::close(fd_);
  }
  ++segment_;
  const auto path = cfg_.dir / segment_name(segment_);
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0600);
  if (fd_ < 0) {
    fail("journal: cannot create " + path.string());
    --segment_;  // the next try takes the number again
    return false;
  }
  std::lock_guard lock(mu_);
  ++stats_.segments;
  return true;
}

void JournalWriter::remove_journal() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::error_code ec;
  auto closed = cfg_.dir;
  closed += ".closed";
  std::filesystem::remove_all(closed, ec);
  std::filesystem::rename(cfg_.dir, closed, ec);
  if (ec) {
    errno = ec.value();
    return fail("journal: cannot rename " + cfg_.dir.string() + " to finish it");
  }
  sync_dir(cfg_.dir.parent_path());  // from here on a resume does not bring the room back
  std::filesystem::remove_all(closed, ec);
  std::lock_guard lock(mu_);
  stats_.finished = true;
}

void JournalWriter::remove_old_segments() {
  if (cfg_.keep_all) return;
  const auto segments = list_segments(cfg_.dir);
  if (segments.size() <= cfg_.keep_segments) return;
  std::uint64_t removed = 0;
  for (std::size_t i = 0; i + cfg_.keep_segments < segments.size(); ++i) {
    std::error_code ec;
    if (std::filesystem::remove(segments[i].second, ec)) ++removed;
  }
  sync_dir(cfg_.dir);
  std::lock_guard lock(mu_);
  stats_.removed_segments += removed;
}

std::int64_t JournalWriter::write_batch(std::deque<Record>& batch) {
  std::string text;
  std::uint64_t in_text = 0;  // records in `text`
  std::int64_t newest = -1;
  bool new_segment = false, failed = false;
  std::uint64_t discarded = 0;
  auto put = [&](std::int64_t tick, std::string line) {
    text += line;
    text += '\n';
    ++in_text;
    newest = std::max(newest, tick);
  };
  auto write_out = [&] {
    if (fd_ >= 0 && !text.empty() && !write_all(fd_, text)) {
      fail("journal: write");
      failed = true;
      discarded += in_text;
    } else {
      std::lock_guard lock(mu_);
      stats_.bytes += text.size();
    }
    text.clear();
    in_text = 0;
  };
  for (Record& r : batch) {
    if (failed) {  // the rest of a failed batch: a retry's checkpoint covers it
      ++discarded;
      continue;
    }
    if (fd_ < 0 && !std::holds_alternative<std::unique_ptr<Checkpoint>>(r)) {  // no segment (failing)
      ++discarded;
      continue;
    }
    std::visit(sim::Overloaded{
                   [&](Inputs& x) { put(x.tick, to_input_line(x.tick, x.in)); },
                   [&](Hash& x) {
                     put(x.tick, R"({"tick":)" + std::to_string(x.tick) + R"(,"hash":")" + hex16(x.hash) +
                                     R"(","event_seq":)" + std::to_string(x.event_seq) + "}");
                   },
                   [&](Session& x) {
                     ojson j;
                     j["tick"] = x.tick;
                     j["session"] = session_json(x.s);
                     put(x.tick, j.dump());
                   },
                   [&](Released& x) {
                     put(x.tick, R"({"tick":)" + std::to_string(x.tick) + R"(,"released":)" +
                                     std::to_string(x.player) + "}");
                   },
                   [&](std::unique_ptr<Checkpoint>& cp_record) {
                     const Checkpoint& x = *cp_record;
                     write_out();
                     if (failed) return;
                     if (!open_segment()) {
                       failed = true;
                       ++discarded;
                       return;
                     }
                     new_segment = true;
                     ojson head;
                     head["fts_journal"] = kJournalFormat;
                     head["version"] = cfg_.version;
                     head["room"] = cfg_.room;
                     head["room_id"] = cfg_.room_id;
                     head["private"] = cfg_.is_private;
                     head["segment"] = segment_;
                     head["seed"] = cfg_.seed;
                     head["config"] = ojson::parse(header_config_);
                     ojson cp;
                     cp["tick"] = x.state.tick;
                     cp["checkpoint"] = match_state_to_json(x.state);
                     cp["hash"] = hex16(sim::match_hash(x.state));
                     cp["event_seq"] = x.event_seq;
                     ojson& sessions = cp["sessions"] = ojson::array();
                     for (const auto& s : x.sessions) sessions.push_back(session_json(s));
                     put(x.state.tick, head.dump() + "\n" + cp.dump());
                   },
               },
               r);
  }
  if (!failed) write_out();
  if (!failed && fd_ >= 0 && ::fdatasync(fd_) != 0) {
    fail("journal: fdatasync");
    failed = true;
  }
  if (failed) {
    if (new_segment) {  // its checkpoint is not durable: a resume must not pick it
      std::error_code ec;
      std::filesystem::remove(cfg_.dir / segment_name(segment_), ec);
      --segment_;
    }
    std::lock_guard lock(mu_);
    stats_.discarded += discarded;
    return -1;
  }
  if (new_segment) {
    sync_dir(cfg_.dir);
    remove_old_segments();
    std::lock_guard lock(mu_);
    if (stats_.failing) {  // a retry's checkpoint is durable: journaling goes on from it
      stats_.failing = false;
      stats_.error.clear();
      ++stats_.recoveries;
    }
  }
  std::lock_guard lock(mu_);
  stats_.discarded += discarded;
  return newest;
}

void JournalWriter::run() {
  // The first batch (the segment's checkpoint) waits sync_ms like every other: a server
  // resuming 64 rooms starts 64 writers at once, and their checkpoints are written after
  // the port opens instead of competing with the resume for the cores.
  auto last_sync = Clock::now();
  for (;;) {
    std::deque<Record> batch;
    bool stopping = false;
    {
      std::unique_lock lock(mu_);
      // At most one sync per sync_ms: records gather in the queue meanwhile (a stop or a
      // flush() does not wait).
      wake_.wait_until(lock, last_sync + std::chrono::milliseconds(cfg_.sync_ms),
                       [&] { return stop_ || flush_requested_; });
      writer_idle_ = true;
      wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      writer_idle_ = false;
      batch.swap(queue_);
      stopping = stop_;
    }
    const std::size_t n = batch.size();
    std::int64_t newest = -1;
    if (n > 0) {
      newest = write_batch(batch);
      last_sync = Clock::now();
    }
    {
      std::lock_guard lock(mu_);
      if (n > 0) {
        ++stats_.syncs;
        stats_.records += n;
        synced_ += n;
        if (synced_ >= pushed_) flush_requested_ = false;
        if (newest >= 0 && !stats_.failing) stats_.durable_tick = std::max(stats_.durable_tick, newest);
      }
      if (stopping && queue_.empty()) break;
    }
    done_.notify_all();
  }
  bool finish = false;
  {
    std::lock_guard lock(mu_);
    finish = finish_;
  }
  if (finish && !cfg_.keep_all) remove_journal();
  {
    std::lock_guard lock(mu_);
    exited_ = true;
  }
  done_.notify_all();
}

}  // namespace fts::store
