// The profile writer (issue 41): the tick's side never waits; writes reach the database
// in batches; a database that is down keeps them in the spool until it is back (nothing
// lost, nothing twice); a crashed server's spool is adopted by the next; the queue's bound.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <future>

#include "../../support/temp_dir.hpp"
#include "open_store.hpp"
#include "pg_rig.hpp"
#include "profiles/writer.hpp"

using namespace fts::profiles;
namespace fs = std::filesystem;

namespace {

using fts::test::open_ok;
using fts::test::TempDir;

MatchResult result(int i, const std::string& fp) {
  MatchResult r;
  r.key = "room/1/" + std::to_string(i);
  r.fingerprint = fp;
  r.name = "ann";
  r.ended_unix_s = 5000 + i;
  r.level = i % 7;
  r.coins = i;
  r.knocks = 1;
  r.ending = Ending::quit;
  return r;
}

const std::string kAnn = "aaaa0000000000000000000000000001";

}  // namespace

TEST_CASE("Profile writer: spool lines read back exactly", "[profiles][writer]") {
  const std::vector<Write> all = {Seen{kAnn, "a \"b\" \\ c", 7}, result(3, kAnn), Forget{kAnn}};
  for (const auto& w : all) {
    auto back = read_spool_line(spool_line(w));
    REQUIRE(back);
    CHECK(*back == w);
  }
  CHECK_FALSE(read_spool_line("{\"result\":\"k\",\"fp\":"));  // torn
  CHECK_FALSE(read_spool_line("[1,2]"));
}

TEST_CASE("Profile writer: results reach SQLite once, the spool empties", "[profiles][writer]") {
  TempDir d;
  WriterConfig cfg;
  cfg.url = (d.path / "p.sqlite").string();
  cfg.spool_dir = d.path / "spool";
  cfg.batch = 64;
  {
    Writer w(cfg);
    REQUIRE(w.spool_error().empty());
    CHECK(w.push(Seen{kAnn, "ann", 1}));
    for (int i = 0; i < 300; ++i) CHECK(w.push(result(i, kAnn)));
    CHECK(w.push(result(5, kAnn)));  // again: counted once
    REQUIRE(w.flush());
    const auto st = w.stats();
    CHECK(st.committed == 302);
    CHECK(st.results == 300);
    CHECK(st.duplicates == 1);
    CHECK(st.batches >= 5);
    CHECK(st.connected);
    CHECK(st.pending == 0);
    CHECK(fs::file_size(Writer::spool_files(cfg.spool_dir).at(0)) == 0);
  }
  CHECK(Writer::spool_files(cfg.spool_dir).empty());  // a clean stop removes its spool
  auto s = open_ok(cfg.url);
  CHECK(s->profile(kAnn)->matches == 300);
}

TEST_CASE("Profile writer: a crashed server's spool is adopted, torn line and all", "[profiles][writer]") {
  TempDir d;
  WriterConfig cfg;
  cfg.url = (d.path / "p.sqlite").string();
  cfg.spool_dir = d.path / "spool";
  // Result 1 is already in the database (the crash came after its commit, before the
  // spool was emptied); 2 and 3 are not; the last line was torn by the crash.
  open_ok(cfg.url)->write({result(1, kAnn)});
  fs::create_directories(cfg.spool_dir);
  {
    std::ofstream orphan(cfg.spool_dir / "spool-999999-deadbeef.jsonl");
    orphan << spool_line(result(1, kAnn)) << "\n" << spool_line(result(2, kAnn)) << "\n"
           << spool_line(result(3, kAnn)) << "\n" << spool_line(result(4, kAnn)).substr(0, 20);
  }
  Writer w(cfg);
  REQUIRE(w.flush());
  const auto st = w.stats();
  CHECK(st.adopted == 3);
  CHECK(st.spool_bad_lines == 1);
  CHECK(st.results == 2);
  CHECK(st.duplicates == 1);
  CHECK(open_ok(cfg.url)->profile(kAnn)->matches == 3);
  CHECK(Writer::spool_files(cfg.spool_dir).size() == 1);  // only its own
}

TEST_CASE("Profile writer: the tick's queue is bounded, the rest is dropped and counted", "[profiles][writer]") {
  TempDir d;
  WriterConfig cfg;
  cfg.url = (d.path / "p.sqlite").string();
  cfg.spool_dir = d.path / "spool";
  cfg.max_queued = 8;
  Writer w(cfg);
  // Hold the writer's thread in a query: the tick's pushes pile up in the queue.
  std::promise<void> release;
  std::promise<void> holding;
  auto released = release.get_future().share();
  w.query([&](Store*) {
    holding.set_value();
    released.wait();
  });
  holding.get_future().wait();
  int accepted = 0;
  for (int i = 0; i < 20; ++i) accepted += w.push(result(i, kAnn));
  CHECK(accepted == 8);
  CHECK(w.stats().dropped == 12);
  CHECK(w.stats().queued == 8);
  release.set_value();
  REQUIRE(w.flush());
  CHECK(w.stats().results == 8);
}

TEST_CASE("Profile writer: PostgreSQL stopped mid-match, started again: nothing lost",
          "[profiles][writer][postgresql]") {
  fts::test::PgRig pg;
  if (!pg.available()) {
    WARN("PostgreSQL 15 not available here: skipped");
    CHECK(pg.status() == 77);
    return;
  }
  TempDir d;
  WriterConfig cfg;
  cfg.url = pg.url();
  cfg.spool_dir = d.path / "spool";
  cfg.retry_ms = 100;
  Writer w(cfg);
  for (int i = 0; i < 10; ++i) w.push(result(i, kAnn));
  REQUIRE(w.flush());
  REQUIRE(pg.stop());
  // The game goes on: pushes return at once, the writes wait in the spool.
  for (int i = 10; i < 30; ++i) CHECK(w.push(result(i, kAnn)));
  CHECK_FALSE(w.flush(std::chrono::milliseconds(2000)));
  auto st = w.stats();
  CHECK_FALSE(st.connected);
  CHECK(st.failures >= 1);
  CHECK_FALSE(st.error.empty());
  CHECK(st.pending == 20);
  std::ifstream spool(Writer::spool_files(cfg.spool_dir).at(0));
  std::string line;
  int lines = 0;
  while (std::getline(spool, line)) lines += read_spool_line(line).has_value();
  CHECK(lines == 20);
  REQUIRE(pg.start());
  REQUIRE(w.flush(std::chrono::milliseconds(15000)));
  st = w.stats();
  CHECK(st.connected);
  CHECK(st.reconnects >= 1);
  CHECK(st.results == 30);
  CHECK(open_ok(pg.url())->profile(kAnn)->matches == 30);
}
