// The profile store on SQLite and on a real PostgreSQL 15 (issue 41): migrations, the
// career sums, idempotent results, the leaderboards and their ties, names kept exactly,
// forgetting, and the files it refuses to open.
#include <sqlite3.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include "../../support/temp_dir.hpp"
#include "open_store.hpp"
#include "pg_rig.hpp"
#include "profiles/store.hpp"

using namespace fts::profiles;
namespace fs = std::filesystem;

namespace {

using fts::test::open_ok;
using fts::test::TempDir;

std::string open_error(const std::string& url) {
  auto r = Store::open(url);
  auto* e = std::get_if<std::string>(&r);
  return e ? *e : "";
}

MatchResult result(const std::string& key, const std::string& fp, std::int64_t level, std::int64_t coins,
                   std::int64_t knocks = 0) {
  MatchResult r;
  r.key = key, r.fingerprint = fp, r.name = "p" + fp.substr(0, 3), r.ended_unix_s = 1000;
  r.level = level, r.coins = coins, r.knocks = knocks, r.lives_lost = 3, r.play_ms = 60000;
  return r;
}

void sql_exec(const fs::path& file, const char* statement) {
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open(file.c_str(), &db) == SQLITE_OK);
  REQUIRE(sqlite3_exec(db, statement, nullptr, nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(db);
}

// The same behaviour on both databases.
void career_and_boards(Store& s) {
  const std::string ann = "aaaa0000000000000000000000000001", bob = "bbbb0000000000000000000000000002";
  CHECK(s.write({Seen{ann, "ann", 100}}) == 0);
  auto p = s.profile(ann);
  REQUIRE(p);
  CHECK(p->name == "ann");
  CHECK(p->first_seen == 100);
  CHECK(p->matches == 0);
  CHECK(s.rank(Board::level, ann) == 0);  // no match yet: not on the board

  // Two matches: sums and bests.
  CHECK(s.write({result("r1/1/1", ann, 3, 50, 4), result("r1/2/1", ann, 2, 90, 1)}) == 2);
  p = s.profile(ann);
  CHECK(p->matches == 2);
  CHECK(p->best_level == 3);
  CHECK(p->best_level_coins == 50);
  CHECK(p->most_coins == 90);
  CHECK(p->knocks == 5);
  CHECK(p->lives_lost == 6);
  CHECK(p->play_ms == 120000);
  CHECK(p->first_seen == 100);
  CHECK(p->last_seen == 1000);

  // The same result again (a spool replayed, a resumed room): counted once.
  CHECK(s.write({result("r1/1/1", ann, 3, 50, 4)}) == 0);
  CHECK(s.profile(ann)->matches == 2);
  CHECK(s.results() == 2);

  // Ties on level go to coins; the knocks board sums.
  CHECK(s.write({result("r2/1/7", bob, 3, 70, 1)}) == 1);
  auto top = s.top(Board::level, 10);
  REQUIRE(top.size() == 2);
  CHECK(top[0].fingerprint == bob);
  CHECK(top[1].fingerprint == ann);
  CHECK(s.rank(Board::level, bob) == 1);
  CHECK(s.rank(Board::level, ann) == 2);
  CHECK(s.rank(Board::knocks, ann) == 1);
  CHECK(s.top(Board::knocks, 1).at(0).fingerprint == ann);

  // A name is any bytes a cleaned name may hold, kept exactly (bound, never spliced).
  const std::string hostile = "'); DROP TABLE fts_profiles;--";
  CHECK(s.write({Seen{bob, hostile, 2000}}) == 0);
  CHECK(s.profile(bob)->name == hostile);
  REQUIRE(s.by_name(hostile, 5).size() == 1);
  CHECK(s.by_name(hostile, 5)[0].fingerprint == bob);
  CHECK(s.profiles() == 2);

  // Forgotten: the profile and its results go; the others stay.
  CHECK(s.write({Forget{ann}}) == 0);
  CHECK_FALSE(s.profile(ann));
  CHECK(s.results() == 1);
  CHECK(s.rank(Board::level, bob) == 1);
}

}  // namespace

TEST_CASE("Profile store: SQLite career, boards, idempotent results", "[profiles][store]") {
  TempDir d;
  const auto file = (d.path / "with space" / "profiles.sqlite");
  fs::create_directories(file.parent_path());
  {
    auto s = open_ok(file.string());
    CHECK_FALSE(s->postgresql());
    career_and_boards(*s);
  }
  // Reopened: migrations are not applied twice, the data is there.
  auto s = open_ok("sqlite:" + file.string());
  CHECK(s->profiles() == 1);
}

TEST_CASE("Profile store: a foreign, corrupt or newer SQLite file is refused", "[profiles][store]") {
  TempDir d;
  const auto text = d.path / "notes.txt";
  std::ofstream(text) << "not a database at all, just some text that is long enough\n";
  CHECK_THAT(open_error(text.string()), Catch::Contains("not a SQLite database"));

  const auto other = d.path / "other.sqlite";
  sql_exec(other, "CREATE TABLE invoices (id INTEGER, total REAL)");
  CHECK_THAT(open_error(other.string()), Catch::Contains("a SQLite database of something else (tables: invoices)"));

  const auto newer = d.path / "newer.sqlite";
  open_ok(newer.string());
  sql_exec(newer, "INSERT INTO fts_migrations (version, what) VALUES (99, 'future')");
  CHECK_THAT(open_error(newer.string()), Catch::Contains("schema version 99 is newer"));

  // Pages overwritten in the middle: the quick check at open says so.
  const auto damaged = d.path / "damaged.sqlite";
  {
    auto s = open_ok(damaged.string());
    std::vector<Write> many;
    for (int i = 0; i < 2000; ++i)
      many.push_back(result("k" + std::to_string(i), "f" + std::to_string(i) + std::string(31, '0'), i % 9, i));
    s->write(many);
  }
  {
    std::fstream f(damaged, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(4096 * 3);
    const std::string junk(4096 * 4, '\x5a');
    f.write(junk.data(), static_cast<std::streamsize>(junk.size()));
  }
  const std::string err = open_error(damaged.string());
  CHECK_FALSE(err.empty());
  CHECK_THAT(err, Catch::Contains(damaged.string()));
}

namespace {

// Writes in one batch leave what the same writes one at a time leave (Store::write folds
// a run of them into multi-row statements): a deterministic mix of players seen, results
// (some keys twice in the batch, some already written) and forgets, with ties.
std::vector<Write> mixed_writes(std::uint32_t seed, int count) {
  std::mt19937 rng(seed);
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<std::uint32_t>(n)); };
  std::vector<Write> out;
  for (int i = 0; i < count; ++i) {
    const std::string fp = "f" + std::to_string(pick(12)) + std::string(30, '0');
    const int kind = pick(100);
    if (kind < 35) {
      out.push_back(Seen{fp, "n" + std::to_string(pick(5)), 100 + pick(50)});
    } else if (kind < 96) {
      MatchResult r = result("k" + std::to_string(pick(count / 2)), fp, pick(4), pick(3) * 10, pick(3));
      r.name = "r" + std::to_string(pick(5));
      r.ended_unix_s = 100 + pick(50);
      r.ending = static_cast<Ending>(pick(3));
      out.push_back(r);
    } else {
      out.push_back(Forget{fp});
    }
  }
  return out;
}

// `batched` gets `writes` in batches of `batch`; the reference, one at a time.
void check_batched_as_one_at_a_time(Store& batched, const std::vector<Write>& writes, std::size_t batch) {
  TempDir d;
  auto one = open_ok((d.path / "one.sqlite").string());
  std::size_t fresh_one = 0, fresh_batched = 0;
  const auto results_before = batched.results(), profiles_before = batched.profiles();
  for (const auto& w : writes) fresh_one += one->write({w});
  for (std::size_t i = 0; i < writes.size(); i += batch)
    fresh_batched += batched.write(std::vector<Write>(writes.begin() + static_cast<std::ptrdiff_t>(i),
                                                      writes.begin() + static_cast<std::ptrdiff_t>(
                                                                           std::min(i + batch, writes.size()))));
  CHECK(fresh_batched == fresh_one);
  CHECK(batched.results() - results_before == one->results());
  CHECK(batched.profiles() - profiles_before == one->profiles());
  for (int p = 0; p < 12; ++p) {
    const std::string fp = "f" + std::to_string(p) + std::string(30, '0');
    INFO("player " << fp);
    const auto a = batched.profile(fp), b = one->profile(fp);
    REQUIRE(a.has_value() == b.has_value());
    if (a) CHECK(*a == *b);
  }
  auto mine = [](std::vector<Profile> v) {  // the mix's players only (PostgreSQL has others)
    std::erase_if(v, [](const Profile& p) { return p.fingerprint[0] != 'f'; });
    return v;
  };
  CHECK(mine(batched.top(Board::knocks, 20)) == mine(one->top(Board::knocks, 20)));
}

}  // namespace

namespace {

// What another process sees: a python3 that opens the file, counts, and closes (closing,
// it checkpoints and deletes the WAL if it finds itself the file's last connection).
long long count_elsewhere(const fs::path& file, const std::string& fingerprint) {
  const std::string cmd = "python3 -c 'import sqlite3, sys; print(sqlite3.connect(sys.argv[1]).execute("
                          "\"SELECT COUNT(*) FROM fts_profiles WHERE fingerprint = ?\", (sys.argv[2],)).fetchone()[0])' " +
                          file.string() + " " + fingerprint;
  FILE* out = ::popen(cmd.c_str(), "r");
  REQUIRE(out != nullptr);
  char line[64] = {};
  const bool got = std::fgets(line, sizeof line, out) != nullptr;
  REQUIRE(::pclose(out) == 0);
  REQUIRE(got);
  return std::atoll(line);
}

}  // namespace

// The server opened the file twice at its start (a check, then the writer's connection). The
// second open read the file's first bytes through a descriptor of its own and closed it,
// which dropped the process's locks: the next outside reader to close deleted the WAL, and
// every later write was seen by the writer alone (forget-me "erased", nothing erased).
TEST_CASE("Profile store: a second open keeps the first connection's writes visible", "[profiles][store]") {
  TempDir d;
  const auto file = d.path / "shared.sqlite";
  auto first = open_ok(file.string());
  auto writer = open_ok(file.string());  // while the first is open
  first.reset();
  const std::string ann = "aaaa0000000000000000000000000011", bob = "bbbb0000000000000000000000000012";
  writer->write({Seen{ann, "ann", 100}});
  CHECK(count_elsewhere(file, ann) == 1);
  writer->write({Seen{bob, "bob", 200}, Forget{ann}});
  CHECK(count_elsewhere(file, bob) == 1);
  CHECK(count_elsewhere(file, ann) == 0);
}

TEST_CASE("Profile store: a batch writes what one write at a time writes", "[profiles][store]") {
  TempDir d;
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    INFO("seed " << seed);
    auto whole = open_ok((d.path / ("whole" + std::to_string(seed) + ".sqlite")).string());
    check_batched_as_one_at_a_time(*whole, mixed_writes(seed, 600), 600);
    auto sevens = open_ok((d.path / ("sevens" + std::to_string(seed) + ".sqlite")).string());
    check_batched_as_one_at_a_time(*sevens, mixed_writes(seed, 600), 7);
  }
}

TEST_CASE("Profile store: PostgreSQL 15 career, boards, two servers share it", "[profiles][store][postgresql]") {
  fts::test::PgRig pg;
  if (!pg.available()) {
    WARN("PostgreSQL 15 not available here (pg_temp.sh exit " << pg.status() << "): skipped");
    CHECK(pg.status() == 77);
    return;
  }
  auto a = open_ok(pg.url());
  auto b = open_ok(pg.url());  // a second server: migrations already there
  CHECK(a->postgresql());
  CHECK_THAT(a->where(), Catch::Contains("postgresql postgresql://fts@127.0.0.1:"));
  career_and_boards(*a);
  // What one server wrote, the other's leaderboard shows.
  const std::string cat = "cccc0000000000000000000000000003";
  b->write({result("b/1/1", cat, 9, 1)});
  CHECK(a->top(Board::level, 1).at(0).fingerprint == cat);
  CHECK(a->rank(Board::level, cat) == 1);
  // Batches as one write at a time (against SQLite's one at a time): the same.
  b->write({Forget{cat}});
  check_batched_as_one_at_a_time(*b, mixed_writes(4, 600), 600);
}

TEST_CASE("Profile store: URLs never show a password", "[profiles][store]") {
  CHECK(redact_url("postgresql://ann:secret@db:5432/fts") == "postgresql://ann:***@db:5432/fts");
  CHECK(redact_url("postgresql://db/fts?user=ann&password=secret&sslmode=require") ==
        "postgresql://db/fts?user=ann&password=***&sslmode=require");
  CHECK(redact_url("/var/lib/fts/profiles.sqlite") == "/var/lib/fts/profiles.sqlite");
  CHECK(is_postgresql_url("postgres://x"));
  CHECK_FALSE(is_postgresql_url("sqlite:/x"));
}
