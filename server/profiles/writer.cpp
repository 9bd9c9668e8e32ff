#include "profiles/writer.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

namespace fts::profiles {
namespace {

std::string errno_text(const std::string& what) { return what + ": " + std::strerror(errno); }

bool write_all(int fd, const std::string& bytes) {
  std::size_t off = 0;
  while (off < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + off, bytes.size() - off);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    off += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

std::string spool_line(const Write& w) {
  nlohmann::json j;
  if (const auto* s = std::get_if<Seen>(&w)) {
    j = {{"seen", s->fingerprint}, {"name", s->name}, {"t", s->unix_s}};
  } else if (const auto* r = std::get_if<MatchResult>(&w)) {
    j = {{"result", r->key},    {"fp", r->fingerprint},       {"name", r->name},   {"t", r->ended_unix_s},
         {"level", r->level},   {"coins", r->coins},          {"knocks", r->knocks}, {"lives_lost", r->lives_lost},
         {"play_ms", r->play_ms}, {"ending", to_string(r->ending)}};
  } else if (const auto* f = std::get_if<Forget>(&w)) {
    j = {{"forget", f->fingerprint}};
  }
  // Names are cleaned before they get here; "replace" keeps a line whatever the bytes.
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::optional<Write> read_spool_line(const std::string& line) {
  const auto j = nlohmann::json::parse(line, nullptr, false);
  if (!j.is_object()) return std::nullopt;
  try {
    if (j.contains("seen")) return Seen{j.at("seen").get<std::string>(), j.at("name").get<std::string>(), j.at("t").get<std::int64_t>()};
    if (j.contains("forget")) return Forget{j.at("forget").get<std::string>()};
    if (j.contains("result")) {
      MatchResult r;
      r.key = j.at("result").get<std::string>();
      r.fingerprint = j.at("fp").get<std::string>();
      r.name = j.at("name").get<std::string>();
      r.ended_unix_s = j.at("t").get<std::int64_t>();
      r.level = j.at("level").get<std::int64_t>();
      r.coins = j.at("coins").get<std::int64_t>();
      r.knocks = j.at("knocks").get<std::int64_t>();
      r.lives_lost = j.at("lives_lost").get<std::int64_t>();
      r.play_ms = j.at("play_ms").get<std::int64_t>();
      auto e = ending_from(j.at("ending").get<std::string>());
      if (!e) return std::nullopt;
      r.ending = *e;
      return r;
    }
  } catch (const nlohmann::json::exception&) {
  }
  return std::nullopt;
}

std::vector<std::filesystem::path> Writer::spool_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("spool-", 0) == 0 && n.size() > 6 + 6 && n.substr(n.size() - 6) == ".jsonl") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

Writer::Writer(WriterConfig cfg) : cfg_(std::move(cfg)) {
  stats_.where = is_postgresql_url(cfg_.url) ? "postgresql " + redact_url(cfg_.url) : "sqlite " + cfg_.url;
  if (!open_spool()) return;
  adopt_orphans();
  thread_ = std::thread([this] { run(); });
}

Writer::~Writer() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (spool_fd_ >= 0) {
    // Everything written: the spool goes; else it stays for the next start to adopt.
    if (pending_.empty()) std::filesystem::remove(spool_path_);
    ::close(spool_fd_);
  }
}

bool Writer::open_spool() {
  std::error_code ec;
  std::filesystem::create_directories(cfg_.spool_dir, ec);
  if (ec) {
    spool_error_ = "profile spool: cannot make " + cfg_.spool_dir.string() + ": " + ec.message();
    return false;
  }
  std::random_device rd;
  char name[64];
  std::snprintf(name, sizeof name, "spool-%d-%08x.jsonl", static_cast<int>(::getpid()), rd());
  spool_path_ = cfg_.spool_dir / name;
  spool_fd_ = ::open(spool_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_APPEND, 0600);
  if (spool_fd_ < 0) {
    spool_error_ = errno_text("profile spool: cannot make " + spool_path_.string());
    return false;
  }
  if (::flock(spool_fd_, LOCK_EX | LOCK_NB) != 0) {
    spool_error_ = errno_text("profile spool: cannot lock " + spool_path_.string());
    return false;
  }
  return true;
}

// Spool files that no live process holds are a crashed (or stopped) server's writes not
// yet in the database: copied into ours (durable) before they are removed.
void Writer::adopt_orphans() {
  for (const auto& path : spool_files(cfg_.spool_dir)) {
    if (path == spool_path_) continue;
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {  // a live server's
      ::close(fd);
      continue;
    }
    std::ifstream in(path);
    std::vector<Write> writes;
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      if (auto w = read_spool_line(line)) writes.push_back(std::move(*w));
      else ++stats_.spool_bad_lines;
    }
    if (append_spool(writes)) {
      for (auto& w : writes) pending_.push_back(std::move(w));
      stats_.adopted += writes.size();
      std::filesystem::remove(path);
    }
    ::close(fd);
  }
  stats_.pending = pending_.size();
}

bool Writer::append_spool(const std::vector<Write>& writes) {
  if (writes.empty()) return true;
  std::string bytes;
  for (const auto& w : writes) bytes += spool_line(w) + "\n";
  if (!write_all(spool_fd_, bytes) || ::fdatasync(spool_fd_) != 0) {
    std::lock_guard lock(mu_);
    stats_.error = errno_text("profile spool " + spool_path_.string());
    return false;
  }
  return true;
}

void Writer::truncate_spool() {
  if (::ftruncate(spool_fd_, 0) == 0) (void)::fdatasync(spool_fd_);
}

bool Writer::push(Write w) {
  {
    std::lock_guard lock(mu_);
    if (queue_.size() >= cfg_.max_queued || thread_.get_id() == std::thread::id()) {
      ++stats_.dropped;
      return false;
    }
    queue_.push_back(std::move(w));
    ++stats_.pushed;
    stats_.queued = queue_.size();
  }
  wake_.notify_one();
  return true;
}

bool Writer::query(std::function<void(Store*)> job) {
  {
    std::lock_guard lock(mu_);
    if (queries_.size() < cfg_.max_queries && thread_.joinable()) {
      queries_.push_back(std::move(job));
      wake_.notify_one();
      return true;
    }
  }
  job(nullptr);
  return false;
}

bool Writer::flush(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mu_);
  const std::uint64_t want = stats_.pushed + stats_.adopted;
  flush_waiting_ = true;
  wake_.notify_one();
  const bool all = done_.wait_for(lock, timeout, [&] { return stats_.committed >= want; });
  flush_waiting_ = false;
  return all;
}

WriterStats Writer::stats() const {
  std::lock_guard lock(mu_);
  return stats_;
}

void Writer::try_connect() {
  auto now = std::chrono::steady_clock::now();
  if (store_ || now < next_try_) return;
  next_try_ = now + std::chrono::milliseconds(cfg_.retry_ms);
  auto opened = Store::open(cfg_.url);
  std::lock_guard lock(mu_);
  if (auto* err = std::get_if<std::string>(&opened)) {
    if (stats_.connected || stats_.error != *err) ++stats_.failures;
    stats_.connected = false;
    stats_.error = *err;
    return;
  }
  store_ = std::move(std::get<std::unique_ptr<Store>>(opened));
  if (stats_.failures > 0) ++stats_.reconnects;
  stats_.connected = true;
  stats_.error.clear();
}

void Writer::write_pending() {
  while (store_ && !pending_.empty()) {
    const std::size_t n = std::min(cfg_.batch, pending_.size());
    std::vector<Write> batch(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n));
    std::size_t results = 0;
    for (const auto& w : batch) results += std::holds_alternative<MatchResult>(w);
    try {
      const std::size_t fresh = store_->write(batch);
      pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n));
      if (pending_.empty()) truncate_spool();  // all of it is in the database
      std::lock_guard lock(mu_);
      stats_.committed += n;
      stats_.results += fresh;
      stats_.duplicates += results - fresh;
      ++stats_.batches;
      stats_.pending = pending_.size();
    } catch (const std::exception& e) {
      // The connection is dropped and made again later: a broken one stays broken.
      store_.reset();
      next_try_ = std::chrono::steady_clock::now() + std::chrono::milliseconds(cfg_.retry_ms);
      std::lock_guard lock(mu_);
      ++stats_.failures;
      stats_.connected = false;
      stats_.error = e.what();
      while (!stats_.error.empty() && stats_.error.back() == '\n') stats_.error.pop_back();
    }
    done_.notify_all();
  }
}

void Writer::run_queries(std::deque<std::function<void(Store*)>>& jobs) {
  for (auto& job : jobs) {
    try {
      job(store_.get());
    } catch (const std::exception&) {
      store_.reset();
      job(nullptr);
    }
  }
}

void Writer::run() {
  try_connect();
  write_pending();
  for (;;) {
    std::vector<Write> taken;
    std::deque<std::function<void(Store*)>> jobs;
    bool stopping = false;
    {
      std::unique_lock lock(mu_);
      // Sleep until a write or a query comes, or the next try of a failed database.
      const auto until = (!store_ && !pending_.empty()) ? next_try_ : std::chrono::steady_clock::now() + std::chrono::seconds(5);
      wake_.wait_until(lock, until, [&] { return stop_ || !queue_.empty() || !queries_.empty() || flush_waiting_; });
      taken.assign(std::make_move_iterator(queue_.begin()), std::make_move_iterator(queue_.end()));
      queue_.clear();
      stats_.queued = 0;
      // The queries with the writes, under one lock: a query asked after a write runs
      // after that write was tried (a forget's answer sees it done).
      jobs.swap(queries_);
      stopping = stop_;
    }
    if (!taken.empty()) {
      // Durable first: once in the spool, a crash or a dead database loses nothing.
      const bool spooled = append_spool(taken);
      if (pending_.size() + taken.size() > kMaxPending) {
        std::lock_guard lock(mu_);
        stats_.dropped += taken.size();
        taken.clear();
      }
      (void)spooled;  // not durable (disk full): still written to the database if it can
      for (auto& w : taken) pending_.push_back(std::move(w));
      std::lock_guard lock(mu_);
      stats_.pending = pending_.size();
    }
    try_connect();
    write_pending();
    run_queries(jobs);
    {
      std::lock_guard lock(mu_);
      done_.notify_all();
    }
    if (stopping) break;
  }
}

}  // namespace fts::profiles
