// Players' profiles and careers in a database (issue 41): SQLite (one file, the default)
// or PostgreSQL (a fleet shares one), through SOCI 4, which speaks both with one API (see
// docs/hosting.md for why SOCI). A Store is one connection; it is used by one thread at a
// time (the profile writer's, or the console's own Store).
//
// The schema is numbered migrations (store.cpp kMigrations), applied at open inside one
// transaction each; the database records which it has (fts_migrations). A SQLite file that
// is not a database, or a database of something else, or one from a newer fts-server, is
// refused at open with a message saying which.
//
// Writes are idempotent: a match result carries a key unique to one player's one match
// (MatchResult::key); a second write of the same key changes nothing, so a result written
// twice (a spool replayed after a crash, a resumed room ending the match again) counts once.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace soci {
class session;
}

namespace fts::profiles {

// How a player's match ended.
enum class Ending : std::uint8_t { game_over, quit, closed };
const char* to_string(Ending e);
std::optional<Ending> ending_from(const std::string& s);

// One player's one match, appended once when it ends.
struct MatchResult {
  std::string key;          // unique per player and match (profiles/career.hpp result_key)
  std::string fingerprint;  // the player's identity (32 hex digits)
  std::string name;         // as shown in the match
  std::int64_t ended_unix_s = 0;
  std::int64_t level = 0;       // the highest level the player reached
  std::int64_t coins = 0;       // the most coins the player held
  std::int64_t knocks = 0;      // enemies the player knocked off
  std::int64_t lives_lost = 0;
  std::int64_t play_ms = 0;     // time in the match (playing and shop)
  Ending ending = Ending::game_over;
  bool operator==(const MatchResult&) const = default;
};

// A player connected: the profile is made if new, its name and last-seen updated.
struct Seen {
  std::string fingerprint;
  std::string name;
  std::int64_t unix_s = 0;
  bool operator==(const Seen&) const = default;
};

// The player asked to be forgotten: the profile and its results are erased.
struct Forget {
  std::string fingerprint;
  bool operator==(const Forget&) const = default;
};

using Write = std::variant<Seen, MatchResult, Forget>;

struct Profile {
  std::string fingerprint;
  std::string name;
  std::int64_t first_seen = 0, last_seen = 0;  // unix seconds
  std::int64_t matches = 0;
  std::int64_t best_level = 0;
  std::int64_t best_level_coins = 0;  // the most coins in a match that reached best_level (ties)
  std::int64_t most_coins = 0;
  std::int64_t knocks = 0;
  std::int64_t lives_lost = 0;
  std::int64_t play_ms = 0;
  bool operator==(const Profile&) const = default;
};

// The leaderboards: best level (ties by that match's coins), most knocks (career total).
enum class Board : std::uint8_t { level, knocks };

// The schema version this build writes (the newest migration).
int schema_version();

class Store {
 public:
  // Connects and migrates. `url`: "postgresql://..." (or "postgres://...", any libpq
  // connection URI) or a SQLite file path (made if missing), optionally "sqlite:PATH".
  // A message saying what is wrong when it cannot.
  static std::variant<std::unique_ptr<Store>, std::string> open(const std::string& url);
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  // Applies a batch in one transaction; the match results that were new (a key already
  // written counts 0). Throws std::exception (soci::soci_error) when the database fails;
  // then nothing of the batch is written. The result is the same as writing the batch one
  // item at a time in its order; it is done in a few multi-row statements (Batcher).
  std::size_t write(const std::vector<Write>& batch);

  std::vector<Profile> top(Board board, std::size_t n);
  // 1-based rank on the board; 0: no profile, or no match played.
  std::int64_t rank(Board board, const std::string& fingerprint);
  std::optional<Profile> profile(const std::string& fingerprint);
  // Profiles whose name is `name`, most recently seen first (names are not unique).
  std::vector<Profile> by_name(const std::string& name, std::size_t n);
  std::int64_t profiles();
  // Profiles on the boards: those with a match played.
  std::int64_t ranked();
  std::int64_t results();
  // Whether the connection still works (a cheap query); false: reconnect.
  bool alive();

  bool postgresql() const { return postgresql_; }
  // "sqlite PATH" or "postgresql HOST:PORT/DB" (never a password).
  const std::string& where() const { return where_; }

 private:
  struct Batcher;  // store.cpp: the write statements, prepared once per connection
  Store();
  std::unique_ptr<soci::session> sql_;
  std::unique_ptr<Batcher> batcher_;  // after sql_: destroyed before it
  bool postgresql_ = false;
  std::string where_;
};

// The URL names PostgreSQL.
bool is_postgresql_url(const std::string& url);
// The URL without its password ("postgresql://ann:***@host/db").
std::string redact_url(const std::string& url);

}  // namespace fts::profiles
