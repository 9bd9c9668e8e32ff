// The match's state hash: every field that influences a future tick, in id order, from
// one field table per struct (fts/sim/field_table.hpp): a member added to a struct and
// to no row here does not build. The rows' order and kinds are the hash's contract:
// committed golden hashes, journals and records hold it (tests/unit/match/
// test_determinism.cpp), so rows are not reordered, and a field added later is a
// WhenSet row (mixed only when set, so that the hashes of matches that never set it stay
// what they were).
#include <type_traits>

#include "fts/sim/field_table.hpp"
#include "fts/sim/hash.hpp"
#include "fts/sim/match.hpp"

namespace fts::sim {
namespace {

using fields::field;
using fields::Skip;

// ---- hash kinds: how a member is mixed ----------------------------------------------------

struct Word {};      // an integer, enum, flag or typed id: one 64-bit word
struct Real {};      // a double: its exact bits
struct Text {};      // its length, then its bytes
struct RngWords {};  // the generator's four words
// A flag packed with the struct's other Bit rows into one word (bit `bit`), mixed after
// the struct's other fields.
struct Bit {
  unsigned bit;
};
// A field added after the golden hashes: mixed only when it is not `unset`, after `marker`
// (0: none); a flag that is set is its marker alone.
template <class K, class T>
struct WhenSet {
  K kind;
  T unset;
  std::uint64_t marker;
};
// A struct: its table's fields in place.
template <class Table>
struct Inline {
  Table table;
};
template <class Table>
Inline(Table) -> Inline<Table>;  // clang before 17 deduces no aggregate's arguments
// A vector: its size, then each element by the table.
template <class Table>
struct Each {
  Table table;
};
template <class Table>
Each(Table) -> Each<Table>;
// A map by id: its size, then each {id, value} by the table of Entry.
template <class Entry, class Table>
struct EachById {
  Table table;
};
// One member of a struct, apart from the struct's other fields (which Skip it).
template <auto Member, class K>
struct Part {
  K kind;
};
// Whole-coin prices as integers among the counts, fractional prices as doubles after the
// speeds (the order the hash has always had).
struct WholePrices {};
struct FractionalPrices {};

template <class T>
std::uint64_t word(const T& v) {
  if constexpr (std::is_same_v<T, bool>) return v ? 1 : 0;
  else if constexpr (std::is_enum_v<T>) return static_cast<std::uint64_t>(v);
  else if constexpr (requires { v.value; }) return v.value;  // a typed id
  else return static_cast<std::uint64_t>(v);
}

template <class M, class Table>
void mix_table(Hasher& h, const M& m, const Table& table);

template <class K, class T>
void mix(Hasher& h, const K& kind, const T& v) {
  if constexpr (std::is_same_v<K, Word>) {
    h.add_u64(word(v));
  } else if constexpr (std::is_same_v<K, Real>) {
    h.add_double(v);
  } else if constexpr (std::is_same_v<K, Text>) {
    h.add_string(v);
  } else if constexpr (std::is_same_v<K, RngWords>) {
    for (std::uint64_t w : v.state()) h.add_u64(w);
  } else if constexpr (std::is_same_v<K, WholePrices>) {
    for (const ItemDef& d : item_table())
      if (d.whole_price) h.add_i64(static_cast<Coins>(v[d.item]));
  } else if constexpr (std::is_same_v<K, FractionalPrices>) {
    for (const ItemDef& d : item_table())
      if (!d.whole_price) h.add_double(v[d.item]);
  } else if constexpr (requires { kind.unset; }) {
    if (v == kind.unset) return;
    if (kind.marker) h.add_u64(kind.marker);
    if constexpr (!std::is_same_v<T, bool>) mix(h, kind.kind, v);
  } else {
    mix_struct(h, kind, v);  // Inline, Each, EachById, Part (below; found by ADL)
  }
}

template <class Table, class T>
void mix_struct(Hasher& h, const Inline<Table>& kind, const T& v) {
  mix_table(h, v, kind.table);
}
template <class Table, class T>
void mix_struct(Hasher& h, const Each<Table>& kind, const std::vector<T>& v) {
  h.add_u64(v.size());
  for (const T& x : v) mix_table(h, x, kind.table);
}
template <class Entry, class Table, class Map>  // std::map or sim::IdMap: by id, ascending
void mix_struct(Hasher& h, const EachById<Entry, Table>& kind, const Map& v) {
  h.add_u64(v.size());
  for (const auto& [id, value] : v) mix_table(h, Entry{id, value}, kind.table);
}
template <auto Member, class K, class T>
void mix_struct(Hasher& h, const Part<Member, K>& kind, const T& v) {
  mix(h, kind.kind, v.*Member);
}

template <class M, class Table>
void mix_table(Hasher& h, const M& m, const Table& table) {
  std::uint64_t bits = 0;
  bool any_bit = false;
  fields::for_each(table, [&](const auto& row) {
    using K = std::remove_cvref_t<decltype(row.kind)>;
    if constexpr (std::is_same_v<K, Bit>) {
      bits |= word(row.of(m)) << row.kind.bit;
      any_bit = true;
    } else if constexpr (!fields::is_skip<K>) {
      mix(h, row.kind, row.of(m));
    }
  });
  if (any_bit) h.add_u64(bits);
}

// ---- the tables ------------------------------------------------------------------------------

constexpr auto kVec2Hash = std::make_tuple(field("x", &Vec2::x, Real{}), field("y", &Vec2::y, Real{}));
static_assert(fields::names_every_member<Vec2>(kVec2Hash));

constexpr auto kEconomyHash = std::make_tuple(
    field("coins", &Economy::coins, Word{}), field("lives", &Economy::lives, Word{}),
    field("mass", &Economy::mass, Word{}), field("prices", &Economy::prices, WholePrices{}),
    field("start_coins", &Economy::start_coins, Word{}), field("earned_defeats", &Economy::earned_defeats, Word{}),
    field("earned_interest", &Economy::earned_interest, Word{}), field("spent", &Economy::spent, Word{}),
    field("purchases", &Economy::purchases, Word{}), field("defeats", &Economy::defeats, Word{}),
    field("vmax_u_per_s", &Economy::vmax_u_per_s, Real{}), field("accel_u_per_s2", &Economy::accel_u_per_s2, Real{}),
    field("multiplier", &Economy::multiplier, Real{}), field("prices", &Economy::prices, FractionalPrices{}),
    field("bank", &Economy::bank, Bit{0}), field("rockets", &Economy::rockets, Bit{1}));
static_assert(fields::names_every_member<Economy>(kEconomyHash));

constexpr auto kPlayerHash = std::make_tuple(
    field("id", &Player::id, Word{}), field("name", &Player::name, Text{}),
    field("eco", &Player::eco, Inline{kEconomyHash}), field("ready", &Player::ready, Word{}),
    field("connected", &Player::connected, Word{}),
    field("parked", &Player::parked, WhenSet<Word, bool>{{}, false, 0x9a4ced}), field("ball", &Player::ball, Word{}),
    field("respawn_tick", &Player::respawn_tick, Word{}),
    field("protected_until_tick", &Player::protected_until_tick, WhenSet<Word, std::int64_t>{{}, -1, 0x5a1e1d}),
    field("next_fire_tick", &Player::next_fire_tick, Word{}), field("aim", &Player::aim, Inline{kVec2Hash}));
static_assert(fields::names_every_member<Player>(kPlayerHash));

constexpr auto kBallHash = std::make_tuple(
    field("id", &Ball::id, Word{}), field("pos", &Ball::pos, Inline{kVec2Hash}),
    field("vel", &Ball::vel, Inline{kVec2Hash}), field("radius", &Ball::radius, Real{}),
    field("mass", &Ball::mass, Real{}),
    field("thrust_axes", &Ball::thrust_axes, Skip{}));  // not state: step() clears it
static_assert(fields::names_every_member<Ball>(kBallHash));

constexpr auto kWorldHash = std::make_tuple(field("arena", &World::arena, Skip{}),  // from the config
                                            field("balls", &World::balls, Each{kBallHash}),
                                            field("buffers", &World::buffers, Skip{}));  // the step's memory
static_assert(fields::names_every_member<World>(kWorldHash));

constexpr auto kEnemySpecHash = std::make_tuple(
    field("mass", &EnemySpec::mass, Real{}), field("radius_u", &EnemySpec::radius_u, Real{}),
    field("accel_u_per_s2", &EnemySpec::accel_u_per_s2, Real{}),
    field("vmax_u_per_s", &EnemySpec::vmax_u_per_s, Real{}),
    field("role", &EnemySpec::role, Skip{}));  // mixed by the body, after its goal
static_assert(fields::names_every_member<EnemySpec>(kEnemySpecHash));

constexpr auto kBodyHash = std::make_tuple(
    field("kind", &Body::kind, Word{}), field("owner", &Body::owner, Word{}), field("index", &Body::index, Word{}),
    field("spec", &Body::spec, Inline{kEnemySpecHash}), field("goal", &Body::goal, Inline{kVec2Hash}),
    field("role", &Body::spec, Part<&EnemySpec::role, Word>{}), field("credit", &Body::credit, Word{}),
    field("credit_tick", &Body::credit_tick, Word{}), field("expires_tick", &Body::expires_tick, Word{}));
static_assert(fields::names_every_member<Body>(kBodyHash));

// A body as the match holds it: by its ball's id, mixed first.
struct BodyEntry {
  BallId id;
  Body value;
};
constexpr auto kBodyEntryHash =
    std::make_tuple(field("id", &BodyEntry::id, Word{}), field("body", &BodyEntry::value, Inline{kBodyHash}));

using M = MatchState;
constexpr auto kMatchHash = std::make_tuple(
    field("cfg", &M::cfg, Skip{}),  // fixed for the match: make_match(cfg, seed) makes the rest
    field("phase", &M::phase, Word{}), field("tick", &M::tick, Word{}), field("level", &M::level, Word{}),
    field("levels_cleared", &M::levels_cleared, Word{}), field("shop_deadline_tick", &M::shop_deadline_tick, Word{}),
    field("matches_started", &M::matches_started, Word{}),
    field("lobby_deadline_tick", &M::lobby_deadline_tick, WhenSet<Word, std::int64_t>{{}, -1, 0}),
    field("rng", &M::rng, RngWords{}), field("next_ball_id", &M::next_ball_id, Word{}),
    field("players", &M::players, Each{kPlayerHash}), field("world", &M::world, Inline{kWorldHash}),
    field("physics", &M::physics, Skip{}), field("step_k", &M::step_k, Skip{}),  // from the config
    field("bodies", &M::bodies, EachById<BodyEntry, decltype(kBodyEntryHash)>{kBodyEntryHash}));
static_assert(fields::names_every_member<M>(kMatchHash));

}  // namespace

std::uint64_t match_hash(const MatchState& s) {
  Hasher h;
  mix_table(h, s, kMatchHash);
  return h.value();
}

}  // namespace fts::sim
