// The field-table machinery (internal), after ioquake3's netField_t: a message is a
// struct plus one table of fields, each named once with its key, its type, its range and
// whether it may be absent. From a table come the MessagePack and JSON writers (any
// writer of wire_io.hpp: W is MsgpackWriter, MsgpackCounter or JsonWriter), the reader,
// and for tables over two structs (state and delta entry) the changed-field delta.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include "fts/sim/field_table.hpp"
#include "wire_io.hpp"

namespace fts::protocol::wire {

// ---- value kinds: how one value is written and read ----------------------------------

// An integer in lo..hi, held in any integral or enum type.
template <class T>
struct Int {
  std::int64_t lo, hi;
  template <class W>
  void put(W& w, const T& v) const { w.integer(static_cast<std::int64_t>(v)); }
  void get(MsgpackReader& r, T& v) const { v = static_cast<T>(r.integer(lo, hi)); }
  // Into the range (what a sender does before writing: quantize()).
  void clamp(T& v) const { v = static_cast<T>(std::clamp(static_cast<std::int64_t>(v), lo, hi)); }
};

// A boolean carried as the integer 0 or 1 (input frames).
struct Bit {
  template <class W>
  void put(W& w, bool v) const { w.uinteger(v ? 1 : 0); }
  void get(MsgpackReader& r, bool& v) const { v = r.integer(0, 1) == 1; }
};

struct Bool {
  template <class W>
  void put(W& w, bool v) const { w.boolean(v); }
  void get(MsgpackReader& r, bool& v) const { v = r.boolean(); }
  void clamp(bool&) const {}
};

// A number (integer or float on the wire), finite, in lo..hi.
struct Num {
  double lo, hi;
  template <class W>
  void put(W& w, double v) const { w.number(std::isfinite(v) ? v : 0.0); }
  void get(MsgpackReader& r, double& v) const { v = r.number(lo, hi); }
  void clamp(double& v) const { v = std::clamp(std::isfinite(v) ? v : 0.0, lo, hi); }
};

// Printable ASCII text of min..max bytes.
struct Text {
  std::size_t min, max;
  template <class W>
  void put(W& w, const std::string& v) const { w.str(v); }
  void get(MsgpackReader& r, std::string& v) const { v.assign(view(r)); }
  // The text in the reader's bytes, checked ("" after a failure).
  std::string_view view(MsgpackReader& r) const {
    const std::string_view s = r.str(max);
    if (r.failed()) return {};
    if (s.size() < min) return r.fail(Reject::out_of_range), std::string_view{};
    for (unsigned char c : s)
      if (c < 0x20 || c > 0x7E) return r.fail(Reject::out_of_range), std::string_view{};
    return s;
  }
  // Cut to max, every other byte '?', filled up to min with '?'.
  void clamp(std::string& v) const {
    if (v.size() > max) v.resize(max);
    for (char& c : v)
      if (c < 0x20 || c > 0x7E) c = '?';
    if (v.size() < min) v.resize(min, '?');
  }
};

// Any string of at most max bytes (the hello's name: the server answers a bad one with
// an error that says what is wrong, instead of a silent drop).
struct AnyText {
  std::size_t max;
  template <class W>
  void put(W& w, const std::string& v) const { w.str(v); }
  void get(MsgpackReader& r, std::string& v) const { v.assign(r.str(max)); }
};

// "" or exactly `digits` lower-case hex digits ("" refused when `required`).
struct Hex {
  std::size_t digits;
  bool required = false;
  template <class W>
  void put(W& w, const std::string& v) const { w.str(v); }
  void get(MsgpackReader& r, std::string& v) const {
    // (A hex field may be longer than text: the hello's sealed identity, 224 digits.)
    const std::string_view s = r.str(std::max(kMaxTextBytes, digits));
    if (r.failed()) return;
    if (s.empty() ? required : s.size() != digits) return r.fail(Reject::out_of_range);
    for (char c : s)
      if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return r.fail(Reject::out_of_range);
    v.assign(s);
  }
};

// A one-character key carried as text (a shop item): text of another length reads as 0,
// so that the receiver answers it (PROTOCOL.md 4.6) instead of dropping the datagram.
struct Key {
  template <class W>
  void put(W& w, char v) const { w.str(std::string_view(&v, 1)); }
  void get(MsgpackReader& r, char& v) const {
    const std::string_view s = Text{0, kMaxTextBytes}.view(r);
    v = s.size() == 1 ? s[0] : char{0};
  }
};

// A field whose bad value costs the message nothing but that field (PROTOCOL.md 4.6,
// 4.12): a value of the wrong type, out of range or too long is skipped, the field keeps
// its default, and read_map notes the field's key in the message's `fault` (if it has
// one), so that the receiver answers the message instead of dropping its datagram.
template <class K>
struct Tolerant {
  K kind;
  template <class W, class T>
  void put(W& w, const T& v) const { kind.put(w, v); }
  template <class T>
  void get(MsgpackReader& r, T& v) const {
    const std::size_t start = r.pos();
    kind.get(r, v);
    if (!r.failed()) return;
    v = T{};
    r.skip_faulty(start);
  }
};

// An enum carried by name: names[i] is the wire text of value i.
template <class E, std::size_t N>
struct Named {
  std::array<const char*, N> names;
  template <class W>
  void put(W& w, E v) const { w.str(names[static_cast<std::size_t>(v) % N]); }
  void get(MsgpackReader& r, E& v) const {
    const std::string_view s = r.str(16);
    for (std::size_t i = 0; i < N; ++i)
      if (s == names[i]) return void(v = static_cast<E>(i));
    if (!r.failed()) r.fail(Reject::out_of_range);
  }
};

// An enum carried by name, where a name this side does not know reads as `other`
// (a command the server answers with "op" instead of dropping it).
template <class E, std::size_t N>
struct OpenNamed {
  std::array<const char*, N> names;
  E other;
  template <class W>
  void put(W& w, E v) const { w.str(names[static_cast<std::size_t>(v) % N]); }
  void get(MsgpackReader& r, E& v) const {
    const std::string_view s = Text{0, kMaxTextBytes}.view(r);
    v = other;
    for (std::size_t i = 0; i < N; ++i)
      if (s == names[i]) v = static_cast<E>(i);
  }
};

// A fixed-length array of one kind.
template <class T, std::size_t N, class K>
struct Fixed {
  K kind;
  template <class W>
  void put(W& w, const std::array<T, N>& v) const {
    w.array(N);
    for (const auto& x : v) kind.put(w, x);
  }
  void get(MsgpackReader& r, std::array<T, N>& v) const {
    if (r.array(kMaxPayloadValues) != N && !r.failed()) return r.fail(Reject::garbage);
    for (auto& x : v) kind.get(r, x);
  }
  void clamp(std::array<T, N>& v) const {
    for (auto& x : v) kind.clamp(x);
  }
};

// A list of up to max items of one kind.
template <class T, class K>
struct List {
  std::size_t max;
  K kind;
  template <class W>
  void put(W& w, const std::vector<T>& v) const {
    w.array(v.size());
    for (const auto& x : v) kind.put(w, x);
  }
  void get(MsgpackReader& r, std::vector<T>& v) const {
    const std::size_t n = r.array(max);
    v.clear();
    v.reserve(n);
    for (std::size_t i = 0; i < n && !r.failed(); ++i) kind.get(r, v.emplace_back());
  }
};

// ---- fields ------------------------------------------------------------------------

// A row of a table: fts/sim/field_table.hpp's, the one mechanism of every field table
// (and its check that a table names every member of its struct).
using ::fts::fields::Field;
using ::fts::fields::Presence;

// A field of a struct inside the message, written at the message's level (the welcome's
// shop terms): the same key space, one more member step.
template <class M, class S, class T, class K>
struct SubField {
  std::string_view key;
  S M::*outer;
  T S::*member;
  K kind;
  Presence presence = Presence::required;
  constexpr const T& of(const M& m) const { return (m.*outer).*member; }
  constexpr T& of(M& m) const { return (m.*outer).*member; }
};

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};

template <class M, class F>
bool present(const F& f, const M& m) {
  using T = std::decay_t<decltype(f.of(m))>;
  const T& v = f.of(m);
  if constexpr (requires { f.kind.present(v); }) return f.kind.present(v);
  else if constexpr (is_optional<T>::value) return v.has_value();
  else if (f.presence == Presence::nonzero) return !(v == T{});
  else return true;
}

template <class W, class M, class F>
void put_field(W& w, const F& f, const M& m) {
  if (!present(f, m)) return;
  w.key(f.key);
  if constexpr (is_optional<std::decay_t<decltype(f.of(m))>>::value) f.kind.put(w, *f.of(m));
  else f.kind.put(w, f.of(m));
}

template <class M, class F>
void get_field(MsgpackReader& r, const F& f, M& m) {
  if constexpr (is_optional<std::decay_t<decltype(f.of(m))>>::value) f.kind.get(r, f.of(m).emplace());
  else f.kind.get(r, f.of(m));
}

// ---- maps: a message or a record with named fields ---------------------------------

// {"t": type (if not null), field: value, ...} in table order.
template <class W, class M, class... F>
void write_map(W& w, const char* type, const M& m, const std::tuple<F...>& table) {
  std::size_t n = type ? 1 : 0;
  std::apply([&](const auto&... f) { ((n += present(f, m) ? 1 : 0), ...); }, table);
  w.map(n);
  if (type) {
    w.key("t");
    w.str(type);
  }
  std::apply([&](const auto&... f) { (put_field(w, f, m), ...); }, table);
}

// Reads a map into m (which starts at its defaults): known keys by the table, any other
// key (including "t") skipped unless its value is a bin. A required field missing is
// garbage, and so is a key given twice (validate_value refuses any key twice; the check
// here keeps two lists from merging into something no writer sends even without it).
template <class M, class... F>
void read_map(MsgpackReader& r, M& m, const std::tuple<F...>& table) {
  static_assert(sizeof...(F) <= 64);
  const std::size_t n = r.map(kMaxPayloadValues);
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < n && !r.failed(); ++i) {
    const std::string_view k = r.str(kMaxTextBytes);
    if (r.failed()) return;
    const std::size_t faults = r.faults();
    bool matched = false;
    std::size_t index = 0;
    std::apply(
        [&](const auto&... f) {
          ((matched || (k == f.key ? (seen >> index & 1 ? r.fail(Reject::garbage) : get_field(r, f, m),
                                      seen |= std::uint64_t{1} << index, matched = true)
                                   : (++index, false))),
           ...);
        },
        table);
    if (!matched) r.skip_unknown();
    if constexpr (requires { m.fault = std::string(k); })
      if (r.faults() != faults && m.fault.empty()) m.fault = std::string(k);
  }
  std::size_t index = 0;
  std::apply(
      [&](const auto&... f) {
        ((f.presence == Presence::required && !(seen >> index & 1) ? r.fail(Reject::garbage) : void(), ++index), ...);
      },
      table);
}

// A record written as a positional array of the table's fields (no keys). `arity`
// fields are written (a shorter form of the same record).
template <class W, class M, class... F>
void write_row(W& w, const M& m, const std::tuple<F...>& table, std::size_t arity = sizeof...(F)) {
  w.array(arity);
  std::size_t index = 0;
  std::apply([&](const auto&... f) { ((index++ < arity ? f.kind.put(w, f.of(m)) : void()), ...); }, table);
}

// Reads a positional array of the first `arity` fields of the table.
template <class M, class... F>
void read_row(MsgpackReader& r, M& m, const std::tuple<F...>& table, std::size_t arity) {
  std::size_t index = 0;
  std::apply([&](const auto&... f) { ((index++ < arity ? f.kind.get(r, f.of(m)) : void()), ...); }, table);
}

// ---- synced fields: a state struct S and its delta entry E ---------------------------
// One row per field: the entry's optional member and the state's member it mirrors.
template <class S, class E, class T, class K>
struct Synced {
  std::string_view key;
  std::optional<T> E::*entry;
  T S::*state;
  K kind;
  Presence presence = Presence::optional;
  // The Field view of this row, for write_map / read_map.
  constexpr Field<E, std::optional<T>, K> field() const { return {key, entry, kind, presence}; }
};

// entry = the fields of `now` that differ from `base` (all of them without a base).
template <class S, class E, class... R>
bool diff(const std::tuple<R...>& table, const S& now, const S* base, E& entry) {
  bool any = false;
  std::apply(
      [&](const auto&... f) {
        ((!base || !(base->*f.state == now.*f.state) ? (entry.*f.entry = now.*f.state, any = true) : false), ...);
      },
      table);
  return any;
}

template <class S, class E, class... R>
void apply(const std::tuple<R...>& table, const E& entry, S& state) {
  std::apply([&](const auto&... f) { ((entry.*f.entry ? void(state.*f.state = *(entry.*f.entry)) : void()), ...); },
             table);
}

// Every field of `state` into its wire range, as the table states it.
template <class S, class... R>
void clamp_all(const std::tuple<R...>& table, S& state) {
  std::apply([&](const auto&... f) { (f.kind.clamp(state.*f.state), ...); }, table);
}

template <class... R>
constexpr auto fields_of(const std::tuple<R...>& table) {
  return std::apply([](const auto&... f) { return std::make_tuple(f.field()...); }, table);
}

}  // namespace fts::protocol::wire
