// fts-journal-bench: what the crash-safe journal (issue 15) costs and buys.
//  1. Tick time with and without the journal, in one run: two identical matches stepped
//     in alternation with the same inputs, one of them journaled; p50/p99/max of each.
//  2. Resume time of a long journal: one room played for --minutes with checkpoints every
//     --checkpoint-s (and once without any checkpoint: a straight replay), then read back
//     with read_journal as `fts-server --resume` does. 64 rooms are 64 such reads.
//  3. Disk: bytes written per room per hour, and bytes kept after compaction.
//  4. With --rooms N: the server's whole resume of N such rooms, each in DIR/<code>/ as
//     fts-server writes them (generated here faster than real time, each room ending just
//     before a checkpoint: the worst case), read on every core and opened in a GameHost as
//     `fts-server --resume` does (server/app/room_journals.hpp). --keep DIR keeps the
//     journals, so that `fts-server --resume --journal-dir DIR` can be timed on them too.
// Figures only; nothing passes or fails on time.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "app/game_host.hpp"
#include "app/room_codes.hpp"
#include "app/room_journals.hpp"
#include "fts/sim/bot_player.hpp"
#include "store/journal.hpp"

using namespace fts;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

constexpr std::uint32_t kPlayers = 4;

// Players first..first+3 join at tick 0, then play as the built-in bots
// (common/bot_player.hpp: they push enemies off, shop and ready), and start again after a
// game over.
sim::TickInputs inputs_at(const sim::MatchState& s, std::uint32_t first = 1) {
  sim::TickInputs in;
  for (std::uint32_t id = first; id < first + kPlayers; ++id) {
    if (s.tick == 0) {
      in.joins.push_back({id, "bench" + std::to_string(id)});
      sim::PlayerTick t;
      t.player = id;
      t.commands.push_back({sim::CommandKind::ready, {}, 0});
      in.players.push_back(t);
      continue;
    }
    sim::PlayerTick t = sim::bot_tick(s, id);
    if (s.phase == sim::Phase::game_over) t.commands.push_back({sim::CommandKind::play_again, {}, 0});
    in.players.push_back(t);
  }
  return in;
}

struct Pct {
  double p50, p99, max;
};
Pct pct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  auto at = [&](double q) { return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))]; };
  return {at(0.5), at(0.99), v.back()};
}

std::uint64_t dir_bytes(const fs::path& dir) {
  std::uint64_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += fs::file_size(e.path());
  return n;
}

std::uint64_t tree_bytes(const fs::path& dir) {
  std::uint64_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) n += e.file_size();
  return n;
}

store::JournalConfig journal_config(const fs::path& dir, std::int64_t checkpoint_ticks) {
  store::JournalConfig c;
  c.dir = dir;
  c.version = "bench";
  c.seed = 7;
  c.checkpoint_every_ticks = checkpoint_ticks;
  c.max_queued = 1 << 24;  // played faster than real time: the writer must not drop
  return c;
}

// Plays `ticks` ticks into a journal; returns the final state and the bytes written.
std::pair<sim::MatchState, store::JournalStats> play(const store::JournalConfig& jc, const sim::MatchConfig& cfg,
                                                    std::int64_t ticks, std::uint32_t first = 1) {
  sim::MatchState s = sim::make_match(cfg, jc.seed);
  std::uint32_t seq = 0;
  store::JournalWriter w(jc, cfg, s, 0, {});
  for (std::uint32_t id = first; id < first + kPlayers; ++id)
    w.session(0, {id, "bench" + std::to_string(id), std::string(32, 'a'), false});
  for (std::int64_t i = 0; i < ticks; ++i) {
    const auto in = inputs_at(s, first);
    w.inputs(s.tick, in);
    const std::int64_t t = s.tick;
    seq += server::GameHost::wire_event_count(t, sim::step(s, in));
    w.stepped(s, seq);
  }
  w.flush();
  return {s, w.stats()};
}

double read_ms(const fs::path& dir, std::int64_t& replayed, bool& ok, std::uint64_t want_hash) {
  const auto t0 = Clock::now();
  auto r = store::read_journal(dir);
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  ok = std::holds_alternative<store::ResumedRoom>(r) &&
       sim::match_hash(std::get<store::ResumedRoom>(r).state) == want_hash;
  replayed = ok ? std::get<store::ResumedRoom>(r).ticks_replayed : -1;
  return ms;
}

// Section 4: `rooms` rooms of `ticks` ticks each generated under root (two at a time),
// then resumed as the server does; prints the times.
void rooms_resume(const fs::path& root, const sim::MatchConfig& cfg, int rooms, std::int64_t ticks,
                  std::int64_t checkpoint_ticks) {
  server::RoomCodes codes(99);
  std::vector<std::string> names;
  for (int i = 0; i < rooms; ++i)
    names.push_back(*codes.next([&](const std::string& c) { return std::count(names.begin(), names.end(), c) > 0; }));
  const auto g0 = Clock::now();
  std::vector<std::uint64_t> hashes(names.size());
  std::atomic<std::size_t> next{0};
  auto generate = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < names.size();) {
      auto jc = journal_config(root / names[i], checkpoint_ticks);
      jc.room = names[i];
      jc.room_id = static_cast<std::uint32_t>(i + 1);
      jc.seed = server::room_seed(7, jc.room_id);
      hashes[i] = sim::match_hash(play(jc, cfg, ticks, static_cast<std::uint32_t>(i * kPlayers + 1)).first);
    }
  };
  std::thread helper(generate);
  generate();
  helper.join();
  const double gen_s = std::chrono::duration<double>(Clock::now() - g0).count();

  // Resumed from a copy: the generated journals stay as they are (--keep).
  const fs::path copy = root.string() + ".resumed";
  fs::remove_all(copy);
  fs::copy(root, copy, fs::copy_options::recursive);
  const auto t0 = Clock::now();
  server::JournalRoot dir(copy);
  const auto reads = server::read_room_journals(copy, dir.room_codes(), std::thread::hardware_concurrency());
  const double read_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  server::Options options;
  options.max_rooms = static_cast<std::uint32_t>(rooms);
  const auto config = server::resumed_config(reads).value_or(cfg);
  server::GameHost host(options, config, protocol::ServerKey{});
  host.journal_rooms(journal_config(copy, checkpoint_ticks));  // as the server: each room journals on
  const auto sum = server::resume_rooms(host, reads, config, 0);
  const double total_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  std::size_t equal = 0;
  std::int64_t replayed = 0;
  double slowest_ms = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const server::Room* r = host.room_by_code(names[i]);
    equal += r && sim::match_hash(r->match()) == hashes[i] ? 1 : 0;
  }
  for (const auto& rd : reads) {
    slowest_ms = std::max(slowest_ms, rd.ms);
    if (const auto* room = std::get_if<store::ResumedRoom>(&rd.result)) replayed += room->ticks_replayed;
  }
  std::printf("resume of %d rooms x %.1f min (checkpoint every %lld ticks, %lld ticks replayed in all, %u threads): "
              "read %.0f ms, whole resume (rooms open, journals on) %.0f ms (slowest room %.1f ms); %zu resumed, %zu hashes equal; "
              "journals generated in %.1f s, %.1f MB on disk\n",
              rooms, static_cast<double>(ticks) / cfg.tick_rate_hz / 60.0, static_cast<long long>(checkpoint_ticks),
              static_cast<long long>(replayed), std::thread::hardware_concurrency(), read_ms, total_ms, slowest_ms,
              sum.resumed, equal, gen_s, static_cast<double>(tree_bytes(root)) / 1e6);
}

}  // namespace

int main(int argc, char** argv) {
  double minutes = 10;
  double checkpoint_s = 5;  // the server's default
  std::int64_t tick_ticks = 3000;
  int rooms = 0;
  std::string keep;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--minutes") minutes = std::atof(argv[i + 1]);
    else if (a == "--checkpoint-s") checkpoint_s = std::atof(argv[i + 1]);
    else if (a == "--tick-ticks") tick_ticks = std::atoll(argv[i + 1]);
    else if (a == "--rooms") rooms = std::atoi(argv[i + 1]);
    else if (a == "--keep") keep = argv[i + 1];
    else {
      std::fprintf(stderr, "usage: fts-journal-bench [--minutes M] [--checkpoint-s S] [--tick-ticks N] "
                           "[--rooms N [--keep DIR]]\n");
      return 2;
    }
  }
  sim::MatchConfig cfg;
  cfg.player_lives = 50;
  const fs::path root = fs::temp_directory_path() / ("fts-journal-bench-" + std::to_string(::getpid()));
  fs::remove_all(root);
  const auto cp_ticks = static_cast<std::int64_t>(checkpoint_s * cfg.tick_rate_hz);
  const auto ticks = static_cast<std::int64_t>(minutes * 60 * cfg.tick_rate_hz) - 1;  // just before a checkpoint
  if (rooms > 0) {  // 4. only
    const fs::path dir = keep.empty() ? root : fs::path(keep);
    fs::remove_all(dir);
    rooms_resume(dir, cfg, rooms, ticks, cp_ticks);
    fs::remove_all(dir.string() + ".resumed");
    if (keep.empty()) fs::remove_all(root);
    return 0;
  }

  // 1. Tick time, same run: match A plain, match B journaled, stepped alternately.
  {
    sim::MatchState a = sim::make_match(cfg, 7), b = sim::make_match(cfg, 7);
    auto jc = journal_config(root / "tick", cp_ticks);  // each checkpoint's copy is on the tick path
    jc.max_queued = 16384;             // the server's bound
    store::JournalWriter w(jc, cfg, b, 0, {});
    std::vector<double> plain_us, journaled_us;
    std::uint32_t seq = 0, seq_a = 0;
    // At the real tick rate, as a server runs (the writer syncs every 100 ms meanwhile).
    auto next = Clock::now();
    const auto period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / cfg.tick_rate_hz));
    for (std::int64_t i = 0; i < tick_ticks; ++i) {
      next += period;
      std::this_thread::sleep_until(next);
      const auto in = inputs_at(a);
      auto plain = [&] {
        const auto t0 = Clock::now();
        seq_a += server::GameHost::wire_event_count(a.tick, sim::step(a, in));
        plain_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      };
      auto journaled = [&] {
        const auto t0 = Clock::now();
        w.inputs(b.tick, in);
        seq += server::GameHost::wire_event_count(b.tick, sim::step(b, in));
        w.stepped(b, seq);
        journaled_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      };
      // Which match goes first alternates: the first after the sleep pays for cold caches.
      if (i % 2 == 0) {
        plain();
        journaled();
      } else {
        journaled();
        plain();
      }
    }
    w.flush();
    const auto p = pct(plain_us), j = pct(journaled_us);
    std::printf("tick time over %lld ticks, %u players (us): without journal p50 %.1f p99 %.1f max %.0f | "
                "with journal p50 %.1f p99 %.1f max %.0f | p99 ratio %.2f | level %lld | dropped %llu\n",
                static_cast<long long>(tick_ticks), kPlayers, p.p50, p.p99, p.max, j.p50, j.p99, j.max, j.p99 / p.p99,
                static_cast<long long>(b.level), static_cast<unsigned long long>(w.stats().dropped));
  }

  // 2 and 3. A long room, with and without checkpoints.
  for (const auto& [label, every] : {std::pair<const char*, std::int64_t>{"checkpoints", cp_ticks},
                                     std::pair<const char*, std::int64_t>{"no checkpoint", ticks + 1}}) {
    const fs::path dir = root / label;
    const auto [state, st] = play(journal_config(dir, every), cfg, ticks);
    std::int64_t replayed = 0;
    bool ok = false;
    const double ms = read_ms(dir, replayed, ok, sim::match_hash(state));
    const double hours = static_cast<double>(ticks) / cfg.tick_rate_hz / 3600.0;
    std::printf("%s (every %lld ticks): %.1f min at level %lld; resume %.1f ms (%lld ticks replayed, %s); "
                "64 rooms ~ %.2f s; written %.0f KB/room/hour, kept on disk %.0f KB\n",
                label, static_cast<long long>(every), minutes, static_cast<long long>(state.level), ms,
                static_cast<long long>(replayed), ok ? "hash equal" : "FAILED", ms * 64 / 1000.0,
                static_cast<double>(st.bytes) / hours / 1024.0, static_cast<double>(dir_bytes(dir)) / 1024.0);
  }
  fs::remove_all(root);
  return 0;
}
