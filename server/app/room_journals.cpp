#include "app/room_journals.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

#include "app/log.hpp"
#include "app/room_codes.hpp"
#include "fts/room/match_config_json.hpp"
#include "fts/room/text.hpp"

namespace fts::server {

namespace fs = std::filesystem;

JournalRoot::JournalRoot(fs::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_)) {
    error_ = "--journal-dir: cannot make directory " + dir_.string() + (ec ? ": " + ec.message() : "");
    return;
  }
  const auto lock_path = dir_ / "lock";
  lock_fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (lock_fd_ < 0 || ::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    error_ = "--journal-dir: " + dir_.string() + " is in use by another server (or cannot be locked)";
    return;
  }
  for (const auto& e : fs::directory_iterator(dir_, ec)) {
    const std::string name = e.path().filename().string();
    if (!e.is_directory()) continue;
    if (name.ends_with(".closed")) {
      fs::remove_all(e.path(), ec);
    } else if (std::error_code mec; fs::exists(e.path() / kMovedMark, mec)) {
      // Handed over and confirmed: the room plays at the peer; resumed here it would play twice.
      log_record(spdlog::level::info, "resume_skipped",
                 {{"code", name}, {"reason", "the room was handed over to a peer: its journal goes"}});
      fs::remove_all(e.path(), ec);
    }
  }
}

JournalRoot::~JournalRoot() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

std::vector<std::string> JournalRoot::room_codes() const {
  std::vector<std::string> codes;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir_, ec)) {
    const std::string name = e.path().filename().string();
    if (e.is_directory() && normalize_room_code(name) == name) codes.push_back(name);
  }
  std::sort(codes.begin(), codes.end());
  return codes;
}

std::vector<RoomJournalRead> read_room_journals(const fs::path& dir, const std::vector<std::string>& codes,
                                                unsigned threads) {
  std::vector<RoomJournalRead> reads(codes.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < codes.size();) {
      const auto t0 = std::chrono::steady_clock::now();
      reads[i].code = codes[i];
      reads[i].result = store::read_journal(dir / codes[i]);
      reads[i].ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
  };
  const auto n = std::clamp<std::size_t>(threads, 1, std::max<std::size_t>(1, codes.size()));
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < n; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  return reads;
}

std::optional<sim::MatchConfig> resumed_config(const std::vector<RoomJournalRead>& reads) {
  const store::ResumedRoom* first = nullptr;
  for (const auto& r : reads)
    if (const auto* room = std::get_if<store::ResumedRoom>(&r.result))
      if (!first || room->room_id < first->room_id) first = room;
  if (!first) return std::nullopt;
  return first->config;
}

ResumeSummary resume_rooms(GameHost& host, const std::vector<RoomJournalRead>& reads, const sim::MatchConfig& config,
                           std::uint64_t now_ms) {
  ResumeSummary sum;
  const std::string config_json = room::match_config_to_json(config).dump();
  for (const auto& read : reads) {
    ++sum.rooms;
    auto skip = [&](const std::string& why) {
      ++sum.skipped;
      log_record(spdlog::level::err, "resume_skipped", {{"code", read.code}, {"reason", why}});
    };
    if (const auto* err = std::get_if<std::string>(&read.result)) {
      skip(*err);
      continue;
    }
    const auto& room = std::get<store::ResumedRoom>(read.result);
    for (const auto& why : room.skipped)
      log_record(spdlog::level::warn, "resume_segment_skipped", {{"code", read.code}, {"reason", why}});
    if (!room.damage.empty())
      log_record(spdlog::level::warn, "resume_damage", {{"code", read.code}, {"damage", room.damage}});
    if (room.room != read.code) {
      skip("its journal names room " + room.room + ", not its directory's");
      continue;
    }
    if (room::match_config_to_json(room.config).dump() != config_json) {
      skip("its match config differs from the other rooms' (one server runs one config)");
      continue;
    }
    if (!host.resume_room(room, now_ms)) {
      skip("the server did not take it back (see resume_refused)");
      continue;
    }
    ++sum.resumed;
    sum.sessions += room.sessions.size();
    const Room* r = host.room_by_code(read.code);
    log_record(spdlog::level::info, "resumed",
               {{"room", r ? r->id() : 0}, {"code", read.code}, {"tick", room.state.tick}, {"level", room.state.level},
                {"segment", room.segment}, {"checkpoint_tick", room.checkpoint_tick},
                {"ticks_replayed", room.ticks_replayed}, {"hashes_checked", room.hashes_checked},
                {"sessions", room.sessions.size()}, {"event_seq", room.event_seq},
                {"hash", room::hex16(sim::match_hash(room.state))}, {"ms", read.ms}});
  }
  return sum;
}

}  // namespace fts::server
