// The profile store's batched writes (Store::write): a batch of results, sightings and
// forgets in a few multi-row statements, prepared once per connection. store.cpp has the
// schema, the connection and the reads.
#include "profiles/store.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include <soci/soci.h>

namespace fts::profiles {

// Where a batch's time went (fts-profile-bench, 2026-12-05): on PostgreSQL, two round trips
// per result (the result, then the career), ~1 000 per batch of 500; on SQLite, the commit
// (the WAL's pages and their fsync) and the B-tree pages read and spilled through a 2 MB
// page cache. So a batch is now a few multi-row statements, prepared once per connection,
// and SQLite gets a larger page cache and checkpoints less often (Store::open).
namespace batch_sql {  // named: Store::Batcher, declared in store.hpp, holds these types

// Rows per statement at most: a batch goes in chunks of the largest powers of two that fit
// (500 = 256 + 128 + 64 + 32 + 16 + 4), so a connection prepares at most 9 sizes of each
// statement. 256 rows x 11 columns stays far below PostgreSQL's 65 535 parameters and
// SQLite's 32 766.
constexpr std::size_t kMaxRows = 256;

// The multi-row statements. Columns: 't' text, 'i' integer, in the order of the list.
struct Shape {
  const char* head;  // "INSERT INTO ... (columns)"
  const char* columns;
  const char* tail;   // after the VALUES rows
  const char* extra;  // after the tail
  bool returns;       // RETURNING one text column
};

// The career's right-hand sides read the row before the update (SQL), so the order of the
// assignments does not matter. `excluded` is a whole run's fold of one player's results
// (Batcher::run), which the CASEs and sums take in as they took one result at a time.
constexpr const char* kCareerUpdate =
    "ON CONFLICT (fingerprint) DO UPDATE SET "
    "matches = fts_profiles.matches + excluded.matches, "
    "best_level_coins = CASE WHEN excluded.best_level > fts_profiles.best_level OR "
    "(excluded.best_level = fts_profiles.best_level AND excluded.best_level_coins > "
    "fts_profiles.best_level_coins) THEN excluded.best_level_coins ELSE fts_profiles.best_level_coins END, "
    "best_level = CASE WHEN excluded.best_level > fts_profiles.best_level THEN excluded.best_level "
    "ELSE fts_profiles.best_level END, "
    "most_coins = CASE WHEN excluded.most_coins > fts_profiles.most_coins THEN excluded.most_coins "
    "ELSE fts_profiles.most_coins END, "
    "knocks = fts_profiles.knocks + excluded.knocks, "
    "lives_lost = fts_profiles.lives_lost + excluded.lives_lost, "
    "play_ms = fts_profiles.play_ms + excluded.play_ms, "
    "last_seen = CASE WHEN excluded.last_seen > fts_profiles.last_seen THEN excluded.last_seen ELSE "
    "fts_profiles.last_seen END";
constexpr const char* kCareerHead =
    "INSERT INTO fts_profiles (fingerprint, name, first_seen, last_seen, matches, best_level, "
    "best_level_coins, most_coins, knocks, lives_lost, play_ms)";

enum class Kind : std::uint8_t { result, seen, career, career_renamed };
constexpr std::array<Shape, 4> kShapes = {{
    // Kind::result: the new keys come back; a key already there is left as it is.
    {"INSERT INTO fts_results (result_key, fingerprint, name, ended, level, coins, knocks, lives_lost, play_ms, "
     "ending)",
     "tttiiiiiit", "ON CONFLICT (result_key) DO NOTHING RETURNING result_key", "", true},
    // Kind::seen: players only seen in the run (no new result).
    {"INSERT INTO fts_profiles (fingerprint, name, first_seen, last_seen)", "ttii",
     "ON CONFLICT (fingerprint) DO UPDATE SET name = excluded.name, last_seen = CASE WHEN excluded.last_seen > "
     "fts_profiles.last_seen THEN excluded.last_seen ELSE fts_profiles.last_seen END",
     "", false},
    // Kind::career: players with new results, their name as it was.
    {kCareerHead, "ttiiiiiiiii", kCareerUpdate, "", false},
    // Kind::career_renamed: ... seen (renamed) after their first result of the run.
    {kCareerHead, "ttiiiiiiiii", kCareerUpdate, ", name = excluded.name", false},
}};

// One player's items of a run folded into one row, as one at a time would leave them.
struct Folded {
  std::string fingerprint, name;
  long long first = 0, last = 0, matches = 0, level = 0, level_coins = 0, coins = 0, knocks = 0, lives = 0,
            play = 0;
  bool results = false;  // a new result (else: only Seen)
  bool renamed = false;  // a Seen came after the results
};

// Where the run from `begin` ends: at a Forget (it erases results, whose keys may come
// again), or at a result of a player seen earlier in the run. A Seen makes a profile with
// zeros that a later result's CASEs compare against, and whether an earlier result of the
// player made it first depends on that result being new, known only once written; with
// every player's results before its Seens, the fold (Batcher::run) is exact.
std::size_t run_end(const std::vector<Write>& batch, std::size_t begin) {
  std::unordered_set<std::string_view> seen;
  std::size_t i = begin;
  for (; i < batch.size(); ++i) {
    const Write& w = batch[i];
    if (std::holds_alternative<Forget>(w)) break;
    if (const auto* s = std::get_if<Seen>(&w)) seen.insert(s->fingerprint);
    else if (seen.count(std::get<MatchResult>(w).fingerprint)) break;
  }
  return i;
}

}  // namespace batch_sql

using namespace batch_sql;

struct Store::Batcher {
  // A prepared multi-row statement and the values it is bound to (sized once, never moved).
  struct Multi {
    explicit Multi(soci::session& sql) : st(sql) {}
    soci::statement st;
    std::vector<std::string> text;
    std::vector<long long> num;
    std::string returned;
  };

  explicit Batcher(soci::session& s) : sql(s), forget_results(s), forget_profile(s) {
    forget_results = (sql.prepare << "DELETE FROM fts_results WHERE fingerprint = :f", soci::use(forget_fp));
    forget_profile = (sql.prepare << "DELETE FROM fts_profiles WHERE fingerprint = :f", soci::use(forget_fp));
  }

  Multi& statement(Kind kind, std::size_t rows) {
    auto& slot = prepared[{kind, rows}];
    if (slot) return *slot;
    const Shape& shape = kShapes[static_cast<std::size_t>(kind)];
    const std::string_view cols = shape.columns;
    const auto texts = static_cast<std::size_t>(std::count(cols.begin(), cols.end(), 't'));
    slot = std::make_unique<Multi>(sql);
    Multi& m = *slot;
    m.text.resize(rows * texts);
    m.num.resize(rows * (cols.size() - texts));
    // Every placeholder its own name: SQLite binds one value to all places of a name.
    std::string q = shape.head;
    q += " VALUES ";
    std::size_t t = 0, n = 0, p = 0;
    for (std::size_t r = 0; r < rows; ++r) {
      q += r ? ", (" : "(";
      for (std::size_t c = 0; c < cols.size(); ++c) {
        q.append(c ? ", :p" : ":p").append(std::to_string(p++));
        if (cols[c] == 't') m.st.exchange(soci::use(m.text[t++]));
        else m.st.exchange(soci::use(m.num[n++]));
      }
      q += ")";
    }
    q.append(" ").append(shape.tail).append(shape.extra);
    if (shape.returns) m.st.exchange(soci::into(m.returned));
    m.st.alloc();
    m.st.prepare(q);
    m.st.define_and_bind();
    return m;
  }

  // Runs `kind` over rows [0, count) in chunks; `fill(multi, chunk_row, row)` sets a row's
  // values; the RETURNING rows go to `returned`.
  template <class Fill>
  void each_chunk(Kind kind, std::size_t count, Fill fill, std::unordered_set<std::string>* returned = nullptr) {
    for (std::size_t done = 0; done < count;) {
      std::size_t rows = kMaxRows;
      while (rows > count - done) rows /= 2;
      Multi& m = statement(kind, rows);
      for (std::size_t r = 0; r < rows; ++r) fill(m, r, done + r);
      if (m.st.execute(true) && returned) {
        do returned->insert(m.returned);
        while (m.st.fetch());
      }
      done += rows;
    }
  }

  void forget(const std::string& fingerprint) {
    forget_fp = fingerprint;
    forget_results.execute(true);
    forget_profile.execute(true);
  }

  // Writes batch[begin, end) (no Forget in it; run_end): the results, then each player's
  // profile once. The match results that were new.
  std::size_t run(const std::vector<Write>& batch, std::size_t begin, std::size_t end) {
    results.clear();
    for (std::size_t i = begin; i < end; ++i)
      if (const auto* r = std::get_if<MatchResult>(&batch[i])) results.push_back(r);
    new_keys.clear();
    each_chunk(
        Kind::result, results.size(),
        [&](Multi& m, std::size_t r, std::size_t i) {
          const MatchResult& x = *results[i];
          std::string* t = &m.text[r * 4];
          long long* n = &m.num[r * 6];
          t[0] = x.key, t[1] = x.fingerprint, t[2] = x.name, t[3] = to_string(x.ending);
          n[0] = x.ended_unix_s, n[1] = x.level, n[2] = x.coins, n[3] = x.knocks, n[4] = x.lives_lost;
          n[5] = x.play_ms;
        },
        &new_keys);

    // Each player's items in order, folded. A result is new where its key came back, at
    // its first place in the run (a key twice in a run is written once).
    folded.clear();
    index.clear();
    std::size_t fresh = 0;
    for (std::size_t i = begin; i < end; ++i) {
      if (const auto* s = std::get_if<Seen>(&batch[i])) {
        auto [it, added] = index.try_emplace(s->fingerprint, folded.size());
        if (added) {
          Folded& f = folded.emplace_back();
          f.fingerprint = s->fingerprint, f.name = s->name, f.first = f.last = s->unix_s;
          continue;
        }
        Folded& f = folded[it->second];
        f.name = s->name;
        f.last = std::max(f.last, static_cast<long long>(s->unix_s));
        f.renamed = f.results;
      } else if (const auto* r = std::get_if<MatchResult>(&batch[i])) {
        if (new_keys.erase(r->key) == 0) continue;
        ++fresh;
        auto [it, added] = index.try_emplace(r->fingerprint, folded.size());
        if (added) {
          Folded& f = folded.emplace_back();
          f.fingerprint = r->fingerprint, f.name = r->name, f.first = f.last = r->ended_unix_s, f.matches = 1;
          f.level = r->level, f.level_coins = f.coins = r->coins, f.knocks = r->knocks, f.lives = r->lives_lost;
          f.play = r->play_ms, f.results = true;
          continue;
        }
        Folded& f = folded[it->second];  // f.results: in a run, a player's results come before its Seens
        ++f.matches;
        if (r->level > f.level || (r->level == f.level && r->coins > f.level_coins)) f.level_coins = r->coins;
        f.level = std::max(f.level, static_cast<long long>(r->level));
        f.coins = std::max(f.coins, static_cast<long long>(r->coins));
        f.knocks += r->knocks, f.lives += r->lives_lost, f.play += r->play_ms;
        f.last = std::max(f.last, static_cast<long long>(r->ended_unix_s));
      }
    }

    for (Kind kind : {Kind::seen, Kind::career, Kind::career_renamed}) {
      targets.clear();
      for (const Folded& f : folded) {
        const Kind k = !f.results ? Kind::seen : f.renamed ? Kind::career_renamed : Kind::career;
        if (k == kind) targets.push_back(&f);
      }
      if (kind == Kind::seen) {
        each_chunk(kind, targets.size(), [&](Multi& m, std::size_t r, std::size_t i) {
          const Folded& f = *targets[i];
          m.text[r * 2] = f.fingerprint, m.text[r * 2 + 1] = f.name;
          m.num[r * 2] = f.first, m.num[r * 2 + 1] = f.last;
        });
        continue;
      }
      each_chunk(kind, targets.size(), [&](Multi& m, std::size_t r, std::size_t i) {
        const Folded& f = *targets[i];
        m.text[r * 2] = f.fingerprint, m.text[r * 2 + 1] = f.name;
        long long* n = &m.num[r * 9];
        n[0] = f.first, n[1] = f.last, n[2] = f.matches, n[3] = f.level, n[4] = f.level_coins, n[5] = f.coins;
        n[6] = f.knocks, n[7] = f.lives, n[8] = f.play;
      });
    }
    return fresh;
  }

  soci::session& sql;
  std::map<std::pair<Kind, std::size_t>, std::unique_ptr<Multi>> prepared;
  std::string forget_fp;
  soci::statement forget_results, forget_profile;
  // Scratch of run(), kept for its capacity.
  std::vector<const MatchResult*> results;
  std::unordered_set<std::string> new_keys;
  std::vector<Folded> folded;
  std::unordered_map<std::string, std::size_t> index;
  std::vector<const Folded*> targets;
};

Store::Store() = default;
Store::~Store() = default;

std::size_t Store::write(const std::vector<Write>& batch) {
  auto& sql = *sql_;
  if (!batcher_) batcher_ = std::make_unique<Batcher>(sql);
  std::size_t fresh = 0;
  soci::transaction tr(sql);
  for (std::size_t i = 0; i < batch.size();) {
    if (const auto* f = std::get_if<Forget>(&batch[i])) {
      batcher_->forget(f->fingerprint);
      ++i;
      continue;
    }
    const std::size_t end = run_end(batch, i);
    fresh += batcher_->run(batch, i, end);
    i = end;
  }
  tr.commit();
  return fresh;
}

}  // namespace fts::profiles
