// The checkpoint's kinds (internal to match_state_json.cpp) for the one field-table
// mechanism (fts/sim/field_table.hpp): a struct is one table of fields, each named once
// with its key and its kind, and the table drives both the writer and the reader. A table
// is written as a JSON object (keys) or as a positional array (a row: balls and bodies are
// many). Every member of the struct has a row in its table, those left out of the file
// included (`Skip`), and names_every_member() checks that at compile time: a member added
// to a struct and not to its table does not build. nlohmann-json here, not the wire's
// byte-driven readers: a checkpoint is a file record (ARCHITECTURE.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <limits>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "fts/sim/field_table.hpp"
#include "fts/sim/id.hpp"
#include "fts/sim/rng.hpp"

namespace fts::store::checkpoint {

using nlohmann::json;

// The rows, the member count and the check are the one field-table mechanism's.
using ::fts::fields::field;
using ::fts::fields::names_every_member;
using ::fts::fields::Presence;
using ::fts::fields::Skip;  // a member made again by make_match(config, seed) (the config, the
                     // arena, the physics) or not state at all (a step's memory): never written

// `what` of the value in j, as a message that names the path to it.
[[noreturn]] inline void rethrow_at(std::string_view where, const std::exception& e) {
  throw std::invalid_argument(std::string(where) + ": " + e.what());
}

// ---- value kinds ------------------------------------------------------------------------

// A JSON value as T, refused unless it is one: an integer field takes only an integer in
// T's range (a float like 6e19 converted to an integer is undefined behaviour; found by
// fts_fuzz_journal), a floating field any number, the rest as nlohmann reads them.
template <class T>
T read_as(const json& j) {
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    const auto out_of_range = [&] { return std::invalid_argument("out of range, got " + j.dump()); };
    if (j.is_number_unsigned()) {
      const auto u = j.get<std::uint64_t>();
      if (u > static_cast<std::uint64_t>(std::numeric_limits<T>::max())) throw out_of_range();
      return static_cast<T>(u);
    }
    if (j.is_number_integer()) {
      const auto i = j.get<std::int64_t>();
      if (i < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
          (i > 0 && static_cast<std::uint64_t>(i) > static_cast<std::uint64_t>(std::numeric_limits<T>::max())))
        throw out_of_range();
      return static_cast<T>(i);
    }
    throw std::invalid_argument("must be an integer, got " + j.dump());
  } else if constexpr (std::is_floating_point_v<T>) {
    if (!j.is_number()) throw std::invalid_argument("must be a number, got " + j.dump());
    return j.get<T>();
  } else {
    return j.get<T>();
  }
}

// A number, boolean or string as itself.
template <class T>
struct Value {
  json put(const T& v) const { return v; }
  void get(const json& j, T& v) const { v = read_as<T>(j); }
};

// A typed id as its number.
struct IdValue {
  template <class Tag>
  json put(sim::Id<Tag> v) const { return v.value; }
  template <class Tag>
  void get(const json& j, sim::Id<Tag>& v) const { v = read_as<std::uint32_t>(j); }
};

// An enum as its number, 0..last.
template <class E>
struct Enum {
  E last;
  json put(E v) const { return static_cast<int>(v); }
  void get(const json& j, E& v) const {
    const auto n = read_as<std::uint64_t>(j);
    if (n > static_cast<std::uint64_t>(last)) throw std::invalid_argument("out of range, got " + j.dump());
    v = static_cast<E>(n);
  }
};
template <class E>
Enum(E) -> Enum<E>;  // clang before 17 deduces no aggregate's arguments

// Exactly N values of one type.
template <class T, std::size_t N>
struct Array {
  json put(const std::array<T, N>& v) const { return v; }
  void get(const json& j, std::array<T, N>& v) const {
    if (!j.is_array() || j.size() != N) throw std::invalid_argument("must be an array of " + std::to_string(N) + " values");
    for (std::size_t i = 0; i < N; ++i) v[i] = read_as<T>(j[i]);
  }
};

// The generator's four words of state.
struct RngState {
  json put(const sim::Rng& r) const { return Array<std::uint64_t, 4>{}.put(r.state()); }
  void get(const json& j, sim::Rng& r) const {
    std::array<std::uint64_t, 4> s{};
    Array<std::uint64_t, 4>{}.get(j, s);
    r.set_state(s);
  }
};

// ---- tables: object and row -------------------------------------------------------------

using ::fts::fields::is_skip;

template <class Table>
struct Splice;
template <class K>
struct is_splice : std::false_type {};
template <class Table>
struct is_splice<Splice<Table>> : std::true_type {};

// Values a field takes in a row: none for Skip, its table's for Splice, else one.
template <class K>
constexpr std::size_t width_of(const K& kind);

template <class Table>
constexpr std::size_t row_width(const Table& table) {
  return std::apply([](const auto&... f) { return (std::size_t{0} + ... + width_of(f.kind)); }, table);
}

// A struct member whose own fields are written at its parent's level (the world's balls
// among the match's keys; a position's x and y among a ball's values).
template <class Table>
struct Splice {
  Table table;
};
template <class Table>
Splice(Table) -> Splice<Table>;

template <class K>
constexpr std::size_t width_of(const K& kind) {
  if constexpr (is_skip<K>) return 0;
  else if constexpr (is_splice<K>::value) return row_width(kind.table);
  else return 1;
}

// Calls value(f) for each field of the table written as a value, splice(f) for each
// Splice field; Skip fields are passed over.
template <class Table, class V, class S>
void visit_fields(const Table& table, V&& value, S&& splice) {
  std::apply(
      [&](const auto&... f) {
        (
            [&] {
              using K = std::decay_t<decltype(f.kind)>;
              if constexpr (is_splice<K>::value) splice(f);
              else if constexpr (!is_skip<K>) value(f);
            }(),
            ...);
      },
      table);
}

// Runs read(); an error it throws is rethrown naming `where` first.
template <class F>
void reading(std::string_view where, F&& read) {
  try {
    read();
  } catch (const std::exception& e) {
    rethrow_at(where, e);
  }
}

template <class M, class Table>
void write_object(json& j, const M& m, const Table& table) {
  visit_fields(
      table, [&](const auto& f) { j[std::string(f.key)] = f.kind.put(m.*f.member); },
      [&](const auto& f) { write_object(j, m.*f.member, f.kind.table); });
}

template <class M, class Table>
void read_object(const json& j, M& m, const Table& table) {
  visit_fields(
      table,
      [&](const auto& f) {
        if (f.presence == Presence::defaulted && !j.contains(f.key)) return;
        reading(f.key, [&] { f.kind.get(j.at(f.key), m.*f.member); });
      },
      [&](const auto& f) { read_object(j, m.*f.member, f.kind.table); });
}

template <class M, class Table>
void write_row(json& row, const M& m, const Table& table) {
  visit_fields(
      table, [&](const auto& f) { row.push_back(f.kind.put(m.*f.member)); },
      [&](const auto& f) { write_row(row, m.*f.member, f.kind.table); });
}

// Reads the table's values from row[at...], advancing `at`.
template <class M, class Table>
void read_row(const json& row, std::size_t& at, M& m, const Table& table) {
  visit_fields(
      table, [&](const auto& f) { reading(f.key, [&] { f.kind.get(row[at++], m.*f.member); }); },
      [&](const auto& f) { read_row(row, at, m.*f.member, f.kind.table); });
}

// Calls read(element) for each element of the array j, naming its index in errors.
template <class F>
void read_elements(const json& j, F&& read) {
  if (!j.is_array()) throw std::invalid_argument("must be an array");
  for (std::size_t i = 0; i < j.size(); ++i) reading(std::to_string(i), [&] { read(j[i]); });
}

// ---- record kinds: a struct inside a value ------------------------------------------------

// A struct as an object of its table's keys.
template <class Table>
struct Object {
  Table table;
  template <class T>
  json put(const T& v) const {
    json j = json::object();
    write_object(j, v, table);
    return j;
  }
  template <class T>
  void get(const json& j, T& v) const {
    if (!j.is_object()) throw std::invalid_argument("must be an object, got " + j.dump());
    read_object(j, v, table);
  }
};
template <class Table>
Object(Table) -> Object<Table>;

// A struct as an array of its table's values, by position.
template <class Table>
struct Row {
  Table table;
  template <class T>
  json put(const T& v) const {
    json j = json::array();
    write_row(j, v, table);
    return j;
  }
  template <class T>
  void get(const json& j, T& v) const {
    const std::size_t n = row_width(table);
    if (!j.is_array() || j.size() != n) throw std::invalid_argument("must be an array of " + std::to_string(n) + " values");
    std::size_t at = 0;
    read_row(j, at, v, table);
  }
};
template <class Table>
Row(Table) -> Row<Table>;

// A vector of records whose ids ascend strictly (the match keeps players and balls so).
template <class K>
struct Ascending {
  K record;
  template <class T>
  json put(const std::vector<T>& v) const {
    json j = json::array();
    for (const T& x : v) j.push_back(record.put(x));
    return j;
  }
  template <class T>
  void get(const json& j, std::vector<T>& v) const {
    v.clear();
    read_elements(j, [&](const json& e) {
      T x{};
      record.get(e, x);
      if (!v.empty() && !(v.back().id < x.id)) throw std::invalid_argument("ids not ascending");
      v.push_back(std::move(x));
    });
  }
};
template <class K>
Ascending(K) -> Ascending<K>;

// A map of records by id, each written as an Entry {id, value} (a row whose first value
// is the id); an id twice is refused.
template <class Entry, class K>
struct ById {
  K entry;
  template <class Map>  // std::map or sim::IdMap: by id, ascending
  json put(const Map& m) const {
    json j = json::array();
    for (const auto& [id, value] : m) j.push_back(entry.put(Entry{id, value}));
    return j;
  }
  template <class Map>
  void get(const json& j, Map& m) const {
    m.clear();
    read_elements(j, [&](const json& e) {
      Entry x{};
      entry.get(e, x);
      if (!m.emplace(x.id, std::move(x.value)).second) throw std::invalid_argument("an id twice");
    });
  }
};

template <class Entry, class K>
constexpr ById<Entry, K> by_id(K entry) {
  return {entry};
}

}  // namespace fts::store::checkpoint
