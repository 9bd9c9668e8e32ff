// fts-profile-bench (issue 41): the profile store's figures, reported, never judged.
//   results/s  match results written in batches (one transaction each, as the writer
//              does) into SQLite and into PostgreSQL: new players and returning ones
//   top 10     the leaderboard query (best level, ties by coins) over N profiles, and a
//              player's rank, median and p99 of repeated queries
//   tick       a 4-bot match stepped at its tick rate (as fts-journal-bench) beside a
//              profile Writer on SQLite, in alternating phases of --phase-s: the writer
//              idle, then busy (a feeder thread keeps two batches waiting, so the writer
//              spools, fsyncs and commits back to back); p50/p99/max tick time of each,
//              and the writer's results/s through its whole path (spool and database)
// PostgreSQL is a throwaway PostgreSQL 15 (tests/support/pg_temp.sh, fsync on, as a host
// runs it); without the postgresql package only SQLite is measured.
//   fts-profile-bench [--profiles N (1000000)] [--results N (100000)] [--batch N (the writer's)]
//                     [--only sqlite|postgresql|tick] [--tick-s S (20)] [--phase-s S (2)]
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "../support/temp_dir.hpp"
#include "../unit/profiles/pg_rig.hpp"
#include "fts/sim/bot_player.hpp"
#include "fts/sim/match.hpp"
#include "profiles/store.hpp"
#include "profiles/writer.hpp"

using namespace fts::profiles;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string fp(std::uint64_t i) {
  char b[33];
  std::snprintf(b, sizeof b, "%016llx%016llx", static_cast<unsigned long long>(i * 0x9E3779B97F4A7C15ull),
                static_cast<unsigned long long>(i));
  return b;
}

MatchResult result(std::uint64_t key, std::uint64_t player) {
  MatchResult r;
  r.key = "bench/" + std::to_string(key);
  r.fingerprint = fp(player);
  r.name = "p" + std::to_string(player % 100000);
  r.ended_unix_s = 1796000000 + static_cast<std::int64_t>(key);
  r.level = static_cast<std::int64_t>((player * 7919 + key) % 40);
  r.coins = static_cast<std::int64_t>((player * 104729 + key) % 5000);
  r.knocks = static_cast<std::int64_t>(key % 13);
  r.lives_lost = 3;
  r.play_ms = 240000;
  r.ending = Ending::game_over;
  return r;
}

// Writes `count` results from key `first` on for players [p0, p0 + players), batched.
double write_rate(Store& s, std::uint64_t first, std::uint64_t count, std::uint64_t p0, std::uint64_t players,
                  std::size_t batch) {
  const auto t0 = Clock::now();
  std::vector<Write> b;
  for (std::uint64_t k = 0; k < count; ++k) {
    b.push_back(result(first + k, p0 + (k % players)));
    if (b.size() == batch || k + 1 == count) {
      s.write(b);
      b.clear();
    }
  }
  return static_cast<double>(count) / seconds_since(t0);
}

void timed_queries(Store& s, const char* what, const char* when) {
  std::vector<double> top_ms, rank_ms;
  for (int i = 0; i < 200; ++i) {
    auto t0 = Clock::now();
    const auto top = s.top(Board::level, 10);
    top_ms.push_back(seconds_since(t0) * 1000);
    t0 = Clock::now();
    (void)s.rank(Board::level, fp(static_cast<std::uint64_t>(i) * 4999));
    rank_ms.push_back(seconds_since(t0) * 1000);
    if (top.size() != 10) std::printf("  (top returned %zu rows)\n", top.size());
  }
  auto pct = [](std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
  };
  std::printf("%-10s top-10 over %lld profiles, %s: median %.3f ms, p99 %.3f ms; rank: median %.3f ms, p99 %.3f ms\n",
              what, static_cast<long long>(s.profiles()), when, pct(top_ms, 0.5), pct(top_ms, 0.99), pct(rank_ms, 0.5),
              pct(rank_ms, 0.99));
}

void run(Store& s, const char* what, std::uint64_t profiles, std::uint64_t results, std::size_t batch) {
  // New players: every result makes a profile (the insert path).
  const double fresh = write_rate(s, 0, results, 0, results, batch);
  // Returning players: results for profiles that exist (the update path).
  const double back = write_rate(s, results, results, 0, results, batch);
  std::printf("%-10s %llu results in batches of %zu: new players %.0f results/s, returning players %.0f results/s\n",
              what, static_cast<unsigned long long>(results), batch, fresh, back);
  if (profiles > results) {
    const auto t0 = Clock::now();
    (void)write_rate(s, 2 * results, profiles - results, results, profiles - results, 5000);
    std::printf("%-10s filled to %llu profiles in %.1f s\n", what, static_cast<unsigned long long>(profiles),
                seconds_since(t0));
  }
  // Twice: right after the fill (the database still settling: PostgreSQL's statistics
  // and cache cold after a million new rows), then again, as a server that has been up
  // a while queries it.
  timed_queries(s, what, "right after the fill");
  timed_queries(s, what, "again");
}


// Players 1..4 join at tick 0, then play as the built-in bots and start again after a
// game over (fts-journal-bench's inputs).
fts::sim::TickInputs bot_inputs(const fts::sim::MatchState& s) {
  using namespace fts::sim;
  TickInputs in;
  for (std::uint32_t id = 1; id <= 4; ++id) {
    if (s.tick == 0) {
      in.joins.push_back({id, "bench" + std::to_string(id)});
      PlayerTick t;
      t.player = id;
      t.commands.push_back({CommandKind::ready, {}, 0});
      in.players.push_back(t);
      continue;
    }
    PlayerTick t = bot_tick(s, id);
    if (s.phase == Phase::game_over) t.commands.push_back({CommandKind::play_again, {}, 0});
    in.players.push_back(t);
  }
  return in;
}

struct Pct {
  double p50, p99, max;
};
Pct pct3(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  auto at = [&](double q) { return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))]; };
  return {at(0.5), at(0.99), v.back()};
}

// The tick beside an idle and a busy profile writer, in alternating phases of one run.
void tick_beside_writer(double tick_s, double phase_s, std::size_t batch) {
  fts::test::TempDir d("fts-profile-bench-tick");
  fts::profiles::WriterConfig wc;
  wc.url = (d.path / "tick.sqlite").string();
  wc.spool_dir = d.path / "spool";
  wc.batch = batch;
  fts::profiles::Writer w(wc);
  if (!w.spool_error().empty()) {
    std::fprintf(stderr, "%s\n", w.spool_error().c_str());
    return;
  }
  std::atomic<bool> busy{false}, done{false};
  std::atomic<std::uint64_t> next_key{1u << 30};
  // Keeps two batches waiting while busy; results of 100 000 players.
  std::thread feeder([&] {
    while (!done) {
      if (!busy) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      const auto st = w.stats();
      if (st.pending + st.queued >= 2 * batch) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      for (std::size_t i = 0; i < batch; ++i) {
        const std::uint64_t k = next_key++;
        if (!w.push(result(k, k % 100000))) break;
      }
    }
  });

  fts::sim::MatchConfig cfg;
  cfg.player_lives = 50;
  fts::sim::MatchState m = fts::sim::make_match(cfg, 7);
  const auto period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / cfg.tick_rate_hz));
  const auto phase_ticks = std::max<std::int64_t>(1, static_cast<std::int64_t>(phase_s * cfg.tick_rate_hz));
  const auto ticks_each = static_cast<std::int64_t>(tick_s * cfg.tick_rate_hz);
  std::vector<double> idle_us, busy_us;
  double busy_seconds = 0;
  std::uint64_t busy_results = 0;
  while (static_cast<std::int64_t>(busy_us.size()) < ticks_each) {
    for (const bool b : {false, true}) {
      auto& out = b ? busy_us : idle_us;
      const auto before = w.stats().results;
      busy = b;
      if (b) std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the writer gets going
      const auto p0 = Clock::now();
      auto next = p0;
      for (std::int64_t i = 0; i < phase_ticks; ++i) {
        next += period;
        std::this_thread::sleep_until(next);
        const auto in = bot_inputs(m);
        const auto t0 = Clock::now();
        (void)fts::sim::step(m, in);
        out.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      }
      if (b) {
        busy_seconds += seconds_since(p0);
        busy_results += w.stats().results - before;
        busy = false;
        (void)w.flush(std::chrono::milliseconds(60000));  // idle again before the next idle phase
      }
    }
  }
  done = true;
  feeder.join();
  const auto i = pct3(idle_us), b = pct3(busy_us);
  std::printf("tick time, %zu ticks each, 4 bots, phases of %.1f s (us): writer idle p50 %.1f p99 %.1f max %.0f | "
              "writer busy p50 %.1f p99 %.1f max %.0f | p99 ratio %.2f | writer while busy: %.0f results/s "
              "(spool + SQLite, batches of %zu), %llu dropped\n",
              idle_us.size(), phase_s, i.p50, i.p99, i.max, b.p50, b.p99, b.max, b.p99 / i.p99,
              static_cast<double>(busy_results) / busy_seconds, batch,
              static_cast<unsigned long long>(w.stats().dropped));
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each figure as it is measured, also into a file
  std::uint64_t profiles = 1000000, results = 100000;
  std::size_t batch = WriterConfig{}.batch;  // as the server's writer batches
  double tick_s = 20, phase_s = 2;
  std::string only;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--profiles") profiles = std::strtoull(v.c_str(), nullptr, 10);
    else if (a == "--results") results = std::strtoull(v.c_str(), nullptr, 10);
    else if (a == "--batch") batch = std::strtoull(v.c_str(), nullptr, 10);
    else if (a == "--only") only = v;
    else if (a == "--tick-s") tick_s = std::atof(v.c_str());
    else if (a == "--phase-s") phase_s = std::atof(v.c_str());
    else {
      std::fprintf(stderr, "fts-profile-bench: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (only.empty() || only == "sqlite") {
    fts::test::TempDir d("fts-profile-bench");
    auto opened = Store::open((d.path / "bench.sqlite").string());
    if (auto* e = std::get_if<std::string>(&opened)) {
      std::fprintf(stderr, "%s\n", e->c_str());
      return 1;
    }
    run(*std::get<std::unique_ptr<Store>>(opened), "sqlite", profiles, results, batch);
  }
  if (only.empty() || only == "postgresql") {
    fts::test::PgRig pg(/*fsync=*/true);
    if (!pg.available()) {
      std::printf("postgresql not measured: PostgreSQL 15 is not installed here\n");
    } else {
      auto opened = Store::open(pg.url());
      if (auto* e = std::get_if<std::string>(&opened)) {
        std::fprintf(stderr, "%s\n", e->c_str());
        return 1;
      }
      run(*std::get<std::unique_ptr<Store>>(opened), "postgresql", profiles, results, batch);
    }
  }
  if ((only.empty() || only == "tick") && tick_s > 0) tick_beside_writer(tick_s, phase_s, batch);
  return 0;
}
