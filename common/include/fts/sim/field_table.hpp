// The one field-table mechanism (issue 38), after ioquake3's netField_t: a struct is
// described by a table, a std::tuple of rows, each naming one member once with its key,
// its kind (how the value is written, read or hashed: each user brings its own kinds) and
// whether it may be absent. The wire's messages (protocol/src/fields.hpp), the checkpoint
// (server/store/checkpoint_fields.hpp), the match configuration (fts/sim/config_fields.hpp)
// and the state hash (common/src/match_hash.cpp) are tables of these rows.
//
// Every table is checked at compile time to name every member of the struct it describes:
//   static_assert(names_every_member<M>(table));
// A member that belongs in no value of the table is still named, by a row of kind Skip or
// in the check's list of members left out on purpose, each with its reason; so a member
// added to a struct and to no table does not build (tests/unit/match/test_field_table.cpp).
// Standard library only: common/ has no I/O and no JSON.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

namespace fts::fields {

enum class Presence : std::uint8_t {
  required,   // always written, must be present
  optional,   // a std::optional member: written when set
  nonzero,    // written unless equal to the default value (0, empty); absent reads as default
  defaulted,  // always written; absent (older writers) keeps the struct's default
};

// One row: the member of M it names, its key, its kind.
template <class M, class T, class K>
struct Field {
  std::string_view key;
  T M::*member;
  K kind;
  Presence presence = Presence::required;
  constexpr const T& of(const M& m) const { return m.*member; }
  constexpr T& of(M& m) const { return m.*member; }
};

template <class M, class T, class K>
constexpr Field<M, T, K> field(std::string_view key, T M::*member, K kind, Presence presence = Presence::required) {
  return {key, member, kind, presence};
}

// The kind of a member that the table names and gives no value: one its user makes again
// (the config of a match made by make_match) or that is not state (a step's memory).
struct Skip {};
template <class K>
inline constexpr bool is_skip = std::is_same_v<std::remove_cvref_t<K>, Skip>;

// Calls fn(row) for each row of the table, in order.
template <class Table, class Fn>
constexpr void for_each(const Table& table, Fn&& fn) {
  std::apply([&](const auto&... row) { (fn(row), ...); }, table);
}

// ---- the member count of an aggregate: the most "anythings" it can be braced from ------
// A shorter list leaves members to their defaults, and a longer one does not compile, so
// the count is found by bisection over 0..kMaxMembers.
struct Anything {
  template <class T>
  operator T() const;  // NOLINT(google-explicit-constructor); declared only: unevaluated use
};

inline constexpr std::size_t kMaxMembers = 160;  // MatchConfig has 105

template <class T, std::size_t... I>
constexpr bool braces_from(std::index_sequence<I...>) {
  return requires { T{(void(I), Anything{})...}; };
}

template <class T, std::size_t Lo = 0, std::size_t Hi = kMaxMembers>
constexpr std::size_t member_count() {
  static_assert(std::is_aggregate_v<T>, "a field table is for an aggregate struct");
  if constexpr (Lo == Hi) {
    return Lo;
  } else {
    constexpr std::size_t mid = (Lo + Hi + 1) / 2;
    if constexpr (braces_from<T>(std::make_index_sequence<mid>{})) return member_count<T, mid, Hi>();
    else return member_count<T, Lo, mid - 1>();
  }
}

// ---- the members a table names ---------------------------------------------------------

struct NoMember {};

// The member of M that a row names: `member`; for a row of a struct inside M (the
// wire's SubField), `outer`; for a row over two structs (the wire's Synced), the one
// whose class is M. A row naming no member of M gives NoMember.
template <class M, class P>
constexpr bool is_member_of = false;
template <class M, class T>
constexpr bool is_member_of<M, T M::*> = true;

template <class P, class M>
concept member_of = is_member_of<M, std::remove_cvref_t<P>>;

template <class M, class Row>
constexpr auto named_member(const Row& row) {
  if constexpr (requires { { row.outer } -> member_of<M>; }) return row.outer;
  else if constexpr (requires { { row.member } -> member_of<M>; }) return row.member;
  else if constexpr (requires { { row.state } -> member_of<M>; }) return row.state;
  else if constexpr (requires { { row.entry } -> member_of<M>; }) return row.entry;
  else if constexpr (member_of<Row, M>) return row;  // a bare member pointer
  else return NoMember{};
}

template <class A, class B>
constexpr bool same_member(const A& a, const B& b) {
  if constexpr (std::is_same_v<A, B> && !std::is_same_v<A, NoMember>) return a == b;
  else return false;
}

template <std::size_t I, class Named>
constexpr bool first_naming(const Named& named) {
  const auto& x = std::get<I>(named);
  if constexpr (std::is_same_v<std::remove_cvref_t<decltype(x)>, NoMember>) {
    return false;
  } else {
    return [&]<std::size_t... J>(std::index_sequence<J...>) {
      return !(same_member(std::get<J>(named), x) || ...);
    }(std::make_index_sequence<I>{});
  }
}

// The number of distinct members of M the rows name (two rows over one member, as the
// snapshot's "balls" and "mv", count once).
template <class M, class... Row>
constexpr std::size_t distinct_members(const Row&... rows) {
  const auto named = std::make_tuple(named_member<M>(rows)...);
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    return (std::size_t{0} + ... + (first_naming<I>(named) ? 1 : 0));
  }(std::index_sequence_for<Row...>{});
}

// True when the table, with the members `left_out` (member pointers: those no row of this
// table names, on purpose), names every member of M.
template <class M, class Table, class... Left>
constexpr bool names_every_member(const Table& table, Left... left_out) {
  static_assert(member_count<M>() < kMaxMembers, "raise kMaxMembers");
  const std::size_t named = std::apply(
      [&](const auto&... rows) { return distinct_members<M>(rows..., left_out...); }, table);
  return named == member_count<M>();
}

}  // namespace fts::fields
