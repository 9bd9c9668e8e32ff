// fts-journal-bench: what the crash-safe journal (issue 15) costs and buys.
//  1. Tick time with and without the journal, in one run: two identical matches stepped
//     in alternation with the same inputs, one of them journaled; p50/p99/max of each.
//  2. Resume time of a long journal: one room played for --minutes with checkpoints every
//     --checkpoint-s (and once without any checkpoint: a straight replay), then read back
//     with read_journal as `fts-server --resume` does. 64 rooms are 64 such reads.
//  3. Disk: bytes written per room per hour, and bytes kept after compaction.
// Figures only; nothing passes or fails on time.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "app/game_host.hpp"
#include "fts/sim/bot_player.hpp"
#include "host/journal.hpp"

using namespace fts;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

constexpr std::uint32_t kPlayers = 4;

// Players join at tick 0, then play as the built-in bots (common/bot_player.hpp: they
// push enemies off, shop and ready), and start again after a game over.
sim::TickInputs inputs_at(const sim::MatchState& s) {
  sim::TickInputs in;
  for (std::uint32_t id = 1; id <= kPlayers; ++id) {
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

host::JournalConfig journal_config(const fs::path& dir, std::int64_t checkpoint_ticks) {
  host::JournalConfig c;
  c.dir = dir;
  c.version = "bench";
  c.seed = 7;
  c.checkpoint_every_ticks = checkpoint_ticks;
  c.max_queued = 1 << 24;  // played faster than real time: the writer must not drop
  return c;
}

// Plays `ticks` ticks into a journal; returns the final state and the bytes written.
std::pair<sim::MatchState, host::JournalStats> play(const fs::path& dir, const sim::MatchConfig& cfg, std::int64_t ticks,
                                                    std::int64_t checkpoint_ticks) {
  sim::MatchState s = sim::make_match(cfg, 7);
  std::uint32_t seq = 0;
  host::JournalWriter w(journal_config(dir, checkpoint_ticks), cfg, s, 0, {});
  for (std::uint32_t id = 1; id <= kPlayers; ++id)
    w.session(0, {id, "bench" + std::to_string(id), std::string(32, 'a'), false});
  for (std::int64_t i = 0; i < ticks; ++i) {
    const auto in = inputs_at(s);
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
  auto r = host::read_journal(dir, &server::GameHost::wire_event_count);
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  ok = std::holds_alternative<host::ResumedRoom>(r) &&
       sim::match_hash(std::get<host::ResumedRoom>(r).state) == want_hash;
  replayed = ok ? std::get<host::ResumedRoom>(r).ticks_replayed : -1;
  return ms;
}

}  // namespace

int main(int argc, char** argv) {
  double minutes = 10;
  double checkpoint_s = 10;
  std::int64_t tick_ticks = 3000;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--minutes") minutes = std::atof(argv[i + 1]);
    else if (a == "--checkpoint-s") checkpoint_s = std::atof(argv[i + 1]);
    else if (a == "--tick-ticks") tick_ticks = std::atoll(argv[i + 1]);
    else {
      std::fprintf(stderr, "usage: fts-journal-bench [--minutes M] [--checkpoint-s S] [--tick-ticks N]\n");
      return 2;
    }
  }
  sim::MatchConfig cfg;
  cfg.player_lives = 50;
  const fs::path root = fs::temp_directory_path() / ("fts-journal-bench-" + std::to_string(::getpid()));
  fs::remove_all(root);

  // 1. Tick time, same run: match A plain, match B journaled, stepped alternately.
  {
    sim::MatchState a = sim::make_match(cfg, 7), b = sim::make_match(cfg, 7);
    auto jc = journal_config(root / "tick", static_cast<std::int64_t>(checkpoint_s * cfg.tick_rate_hz));
    jc.checkpoint_every_ticks = 1000;  // a checkpoint every 10 s: its copy is on the tick path
    jc.max_queued = 16384;             // the server's bound
    host::JournalWriter w(jc, cfg, b, 0, {});
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
  const auto ticks = static_cast<std::int64_t>(minutes * 60 * cfg.tick_rate_hz) - 1;  // just before a checkpoint
  const auto cp_ticks = static_cast<std::int64_t>(checkpoint_s * cfg.tick_rate_hz);
  for (const auto& [label, every] : {std::pair<const char*, std::int64_t>{"checkpoints", cp_ticks},
                                     std::pair<const char*, std::int64_t>{"no checkpoint", ticks + 1}}) {
    const fs::path dir = root / label;
    const auto [state, st] = play(dir, cfg, ticks, every);
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
