#include "profiles/store.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include <soci/postgresql/soci-postgresql.h>
#include <soci/soci.h>
#include <soci/sqlite3/soci-sqlite3.h>

namespace fts::profiles {
namespace {

constexpr const char* kApp = "fear-the-sphere";

// One migration: its number and the statements that take the schema from number - 1 to
// it. Never edit a released one: add the next. Plain SQL that SQLite (>= 3.24) and
// PostgreSQL (>= 9.5) both read (ON CONFLICT, CASE; no GREATEST, no SERIAL).
struct Migration {
  int version;
  const char* what;
  std::vector<const char*> statements;
};

const std::vector<Migration>& migrations() {
  static const std::vector<Migration> m = {
      {1,
       "profiles, match results, leaderboard indexes",
       {"CREATE TABLE fts_meta (key TEXT PRIMARY KEY, value TEXT NOT NULL)",
        "INSERT INTO fts_meta (key, value) VALUES ('app', 'fear-the-sphere')",
        "CREATE TABLE fts_profiles (fingerprint TEXT PRIMARY KEY, name TEXT NOT NULL,"
        " first_seen BIGINT NOT NULL, last_seen BIGINT NOT NULL, matches BIGINT NOT NULL DEFAULT 0,"
        " best_level BIGINT NOT NULL DEFAULT 0, best_level_coins BIGINT NOT NULL DEFAULT 0,"
        " most_coins BIGINT NOT NULL DEFAULT 0, knocks BIGINT NOT NULL DEFAULT 0,"
        " lives_lost BIGINT NOT NULL DEFAULT 0, play_ms BIGINT NOT NULL DEFAULT 0)",
        "CREATE TABLE fts_results (result_key TEXT PRIMARY KEY, fingerprint TEXT NOT NULL, name TEXT NOT NULL,"
        " ended BIGINT NOT NULL, level BIGINT NOT NULL, coins BIGINT NOT NULL, knocks BIGINT NOT NULL,"
        " lives_lost BIGINT NOT NULL, play_ms BIGINT NOT NULL, ending TEXT NOT NULL)",
        "CREATE INDEX fts_results_by_player ON fts_results (fingerprint)",
        "CREATE INDEX fts_profiles_by_level ON fts_profiles (best_level DESC, best_level_coins DESC, fingerprint)",
        "CREATE INDEX fts_profiles_by_knocks ON fts_profiles (knocks DESC, fingerprint)",
        "CREATE INDEX fts_profiles_by_name ON fts_profiles (name, last_seen)"}},
  };
  return m;
}

const char* kProfileColumns =
    "fingerprint, name, first_seen, last_seen, matches, best_level, best_level_coins, most_coins, knocks, "
    "lives_lost, play_ms";

// A profile's columns read into a Profile.
struct ProfileInto {
  Profile p;
  long long first = 0, last = 0, matches = 0, level = 0, level_coins = 0, coins = 0, knocks = 0, lives = 0,
            play = 0;
  template <class S>
  void bind(S& st) {
    st.exchange(soci::into(p.fingerprint));
    st.exchange(soci::into(p.name));
    st.exchange(soci::into(first));
    st.exchange(soci::into(last));
    st.exchange(soci::into(matches));
    st.exchange(soci::into(level));
    st.exchange(soci::into(level_coins));
    st.exchange(soci::into(coins));
    st.exchange(soci::into(knocks));
    st.exchange(soci::into(lives));
    st.exchange(soci::into(play));
  }
  Profile get() {
    Profile out = p;
    out.first_seen = first, out.last_seen = last, out.matches = matches, out.best_level = level;
    out.best_level_coins = level_coins, out.most_coins = coins, out.knocks = knocks, out.lives_lost = lives;
    out.play_ms = play;
    return out;
  }
};

// "SELECT <the profile's columns> FROM fts_profiles <rest>", appended to one named string:
// GCC 12 at -O2 saw out-of-bounds copies in the chain of operator+ temporaries it made
// (-Warray-bounds, a false positive that failed the optimized build).
std::string select_profiles(std::string_view rest) {
  std::string q = "SELECT ";
  q.append(kProfileColumns).append(" FROM fts_profiles ").append(rest);
  return q;
}

std::vector<Profile> fetch_profiles(soci::session& sql, const std::string& query,
                                    const std::vector<std::string>& text_args, const std::vector<long long>& int_args) {
  ProfileInto row;
  soci::statement st(sql);
  row.bind(st);
  for (const auto& t : text_args) st.exchange(soci::use(t));
  for (const auto& i : int_args) st.exchange(soci::use(i));
  st.alloc();
  st.prepare(query);
  st.define_and_bind();
  std::vector<Profile> out;
  if (st.execute(true)) {
    do {
      out.push_back(row.get());
    } while (st.fetch());
  }
  return out;
}

std::string strip_sqlite_prefix(const std::string& url) {
  if (url.rfind("sqlite://", 0) == 0) return url.substr(9);
  if (url.rfind("sqlite:", 0) == 0) return url.substr(7);
  return url;
}

// The tables of a SQLite database (its schema, without SQLite's own).
std::vector<std::string> sqlite_tables(soci::session& sql) {
  std::vector<std::string> names;
  std::string name;
  soci::statement st = (sql.prepare << "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT LIKE "
                                       "'sqlite_%' ORDER BY name",
                        soci::into(name));
  if (st.execute(true)) {
    do names.push_back(name);
    while (st.fetch());
  }
  return names;
}

bool has_table(soci::session& sql, bool pg, const std::string& table) {
  long long n = 0;
  if (pg)
    sql << "SELECT COUNT(*) FROM information_schema.tables WHERE table_schema = current_schema() AND table_name = :t",
        soci::use(table), soci::into(n);
  else
    sql << "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND name = :t", soci::use(table), soci::into(n);
  return n > 0;
}

// The migrations, each in its own transaction; PostgreSQL servers of a fleet starting
// at once take turns (an advisory lock), SQLite processes too (BEGIN IMMEDIATE).
std::optional<std::string> migrate(soci::session& sql, bool pg, const std::string& where) {
  for (const auto& m : migrations()) {
    sql << (pg ? "BEGIN" : "BEGIN IMMEDIATE");
    try {
      if (pg) sql << "SELECT pg_advisory_xact_lock(4141)";
      if (!has_table(sql, pg, "fts_migrations"))
        sql << "CREATE TABLE fts_migrations (version BIGINT PRIMARY KEY, what TEXT NOT NULL)";
      long long have = 0;
      sql << "SELECT COUNT(*) FROM fts_migrations WHERE version = :v", soci::use(static_cast<long long>(m.version)),
          soci::into(have);
      if (have == 0) {
        for (const char* s : m.statements) sql << s;
        const long long v = m.version;
        const std::string what = m.what;
        sql << "INSERT INTO fts_migrations (version, what) VALUES (:v, :w)", soci::use(v), soci::use(what);
      }
      sql << "COMMIT";
    } catch (const std::exception& e) {
      try {
        sql << "ROLLBACK";
      } catch (const std::exception&) {
      }
      return where + ": schema migration " + std::to_string(m.version) + " (" + m.what + ") failed: " + e.what();
    }
  }
  return std::nullopt;
}

// Refuses a database that is not ours, or is newer than this build.
std::optional<std::string> check_ours(soci::session& sql, bool pg, const std::string& where) {
  if (!pg) {
    auto tables = sqlite_tables(sql);
    if (!tables.empty() && !has_table(sql, pg, "fts_meta")) {
      std::string list;
      for (std::size_t i = 0; i < tables.size() && i < 5; ++i) list += (i ? ", " : "") + tables[i];
      return where + ": a SQLite database of something else (tables: " + list +
             "); give --profiles another file, or move this one away";
    }
  }
  if (has_table(sql, pg, "fts_meta")) {
    std::string app;
    soci::indicator ind = soci::i_ok;
    sql << "SELECT value FROM fts_meta WHERE key = 'app'", soci::into(app, ind);
    if (!sql.got_data() || ind != soci::i_ok || app != kApp)
      return where + ": its fts_meta table is not fts-server's (app \"" + app + "\")";
  }
  if (has_table(sql, pg, "fts_migrations")) {
    long long newest = 0;
    soci::indicator ind = soci::i_ok;
    sql << "SELECT MAX(version) FROM fts_migrations", soci::into(newest, ind);
    if (ind == soci::i_ok && newest > schema_version())
      return where + ": schema version " + std::to_string(newest) + " is newer than this fts-server's (" +
             std::to_string(schema_version()) + "): run a newer fts-server";
  }
  return std::nullopt;
}

}  // namespace

const char* to_string(Ending e) {
  switch (e) {
    case Ending::game_over: return "game_over";
    case Ending::quit: return "quit";
    case Ending::closed: return "closed";
  }
  return "?";
}

std::optional<Ending> ending_from(const std::string& s) {
  for (Ending e : {Ending::game_over, Ending::quit, Ending::closed})
    if (s == to_string(e)) return e;
  return std::nullopt;
}

int schema_version() { return migrations().back().version; }

bool is_postgresql_url(const std::string& url) {
  return url.rfind("postgresql://", 0) == 0 || url.rfind("postgres://", 0) == 0;
}

std::string redact_url(const std::string& url) {
  if (!is_postgresql_url(url)) return url;
  const auto scheme_end = url.find("://") + 3;
  const auto at = url.find('@', scheme_end);
  std::string out = url;
  if (at != std::string::npos) {
    const auto colon = url.find(':', scheme_end);
    if (colon != std::string::npos && colon < at) out = url.substr(0, colon + 1) + "***" + url.substr(at);
  }
  // A password given as a query parameter.
  if (auto p = out.find("password="); p != std::string::npos) {
    auto end = out.find('&', p);
    out = out.substr(0, p + 9) + "***" + (end == std::string::npos ? "" : out.substr(end));
  }
  return out;
}

std::variant<std::unique_ptr<Store>, std::string> Store::open(const std::string& url) {
  std::unique_ptr<Store> store(new Store());
  store->postgresql_ = is_postgresql_url(url);
  try {
    if (store->postgresql_) {
      store->where_ = "postgresql " + redact_url(url);
      store->sql_ = std::make_unique<soci::session>(*soci::factory_postgresql(), url);
      *store->sql_ << "SET client_min_messages TO WARNING";
    } else {
      const std::string path = strip_sqlite_prefix(url);
      store->where_ = "sqlite " + path;
      if (path.empty()) return std::string("--profiles: an empty SQLite path");
      if (path.find('"') != std::string::npos) return "--profiles: a SQLite path with a '\"' in it: " + path;
      // The file is read by SQLite alone, never through a descriptor of ours: closing any
      // descriptor of a file drops every POSIX lock this process holds on it, a connection
      // already open here then held none, and the next reader elsewhere to close thought
      // itself the last, checkpointed and deleted the WAL this connection went on writing
      // to (forget-me said "erased" and nobody else saw it: 2026-12-06). A file that is not
      // a database is SQLite's SQLITE_NOTADB at the first statement (below).
      store->sql_ = std::make_unique<soci::session>(*soci::factory_sqlite3(), "db=\"" + path + "\" timeout=10");
      auto& sql = *store->sql_;
      sql << "PRAGMA busy_timeout = 10000";
      std::string mode;
      try {
        sql << "PRAGMA journal_mode = WAL", soci::into(mode);  // the first statement to read the file
      } catch (const soci::sqlite3_soci_error& e) {
        if (e.result() != SQLITE_NOTADB) throw;
        return store->where_ + ": not a SQLite database (a corrupt or foreign file); move it away or give "
                               "--profiles another file";
      }
      sql << "PRAGMA synchronous = FULL";
      // A batch touches pages all over the two tables and their indexes. A 64 MiB page
      // cache (the default is 2 MB) keeps them from being read back and spilled to the WAL
      // mid-transaction; a checkpoint every ~40 MB of WAL (the default: ~4 MB) copies a page
      // to the database once for many commits that changed it. Durability is unchanged:
      // every commit's WAL frames are fsynced (synchronous = FULL) before it returns.
      sql << "PRAGMA cache_size = -65536";
      sql << "PRAGMA wal_autocheckpoint = 10000";
      std::string ok;
      sql << "PRAGMA quick_check(1)", soci::into(ok);
      if (ok != "ok") return store->where_ + ": the database is damaged (" + ok + "); restore it from a backup";
    }
    if (auto err = check_ours(*store->sql_, store->postgresql_, store->where_)) return *err;
    if (auto err = migrate(*store->sql_, store->postgresql_, store->where_)) return *err;
  } catch (const std::exception& e) {
    std::string msg = e.what();
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
    return store->where_ + ": " + msg;
  }
  return store;
}

std::vector<Profile> Store::top(Board board, std::size_t n) {
  const char* query = board == Board::level
                          ? "WHERE matches > 0 ORDER BY best_level DESC, best_level_coins DESC, fingerprint LIMIT :n"
                          : "WHERE matches > 0 ORDER BY knocks DESC, fingerprint LIMIT :n";
  return fetch_profiles(*sql_, select_profiles(query), {}, {static_cast<long long>(n)});
}

std::int64_t Store::rank(Board board, const std::string& fingerprint) {
  auto p = profile(fingerprint);
  if (!p || p->matches == 0) return 0;
  // Those ahead, counted in parts that each read a range of the board's index: one query
  // with OR read every row (2.3 s over 1 000 000 profiles, fts-profile-bench). A profile
  // without a match has level, coins and knocks 0, so it is never strictly ahead: only the
  // full tie (the last part) needs "matches > 0".
  long long higher = 0, tied_higher = 0, tied = 0;
  const long long l = p->best_level, c = p->best_level_coins, k = p->knocks;
  if (board == Board::level) {
    *sql_ << "SELECT COUNT(*) FROM fts_profiles WHERE best_level > :l", soci::use(l), soci::into(higher);
    *sql_ << "SELECT COUNT(*) FROM fts_profiles WHERE best_level = :l AND best_level_coins > :c", soci::use(l),
        soci::use(c), soci::into(tied_higher);
    *sql_ << "SELECT COUNT(*) FROM fts_profiles WHERE best_level = :l AND best_level_coins = :c AND fingerprint < :f "
             "AND matches > 0",
        soci::use(l), soci::use(c), soci::use(fingerprint), soci::into(tied);
  } else {
    *sql_ << "SELECT COUNT(*) FROM fts_profiles WHERE knocks > :k", soci::use(k), soci::into(higher);
    *sql_ << "SELECT COUNT(*) FROM fts_profiles WHERE knocks = :k AND fingerprint < :f AND matches > 0", soci::use(k),
        soci::use(fingerprint), soci::into(tied);
  }
  return higher + tied_higher + tied + 1;
}

std::optional<Profile> Store::profile(const std::string& fingerprint) {
  auto v = fetch_profiles(*sql_, select_profiles("WHERE fingerprint = :f"), {fingerprint}, {});
  if (v.empty()) return std::nullopt;
  return v.front();
}

std::vector<Profile> Store::by_name(const std::string& name, std::size_t n) {
  return fetch_profiles(*sql_, select_profiles("WHERE name = :n ORDER BY last_seen DESC, fingerprint LIMIT :l"),
                        {name}, {static_cast<long long>(n)});
}

std::int64_t Store::profiles() {
  long long n = 0;
  *sql_ << "SELECT COUNT(*) FROM fts_profiles", soci::into(n);
  return n;
}

std::int64_t Store::ranked() {
  long long n = 0;
  *sql_ << "SELECT COUNT(*) FROM fts_profiles WHERE matches > 0", soci::into(n);
  return n;
}

std::int64_t Store::results() {
  long long n = 0;
  *sql_ << "SELECT COUNT(*) FROM fts_results", soci::into(n);
  return n;
}

bool Store::alive() {
  try {
    int one = 0;
    *sql_ << "SELECT 1", soci::into(one);
    return one == 1;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace fts::profiles
