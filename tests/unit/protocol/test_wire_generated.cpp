// Round trips and rejections generated from the field tables (issue 14): every message
// type, every field, in both encodings. A field added to a table is tested here without
// a line of test code: it gets edge values that must round-trip, values just out of its
// range that must be refused (out_of_range), and, if required, its absence (garbage).
#include <catch2/catch.hpp>

#include <limits>
#include <set>
#include <nlohmann/json.hpp>
#include <utility>

#include "fts/protocol/codec.hpp"
#include "json_reader.hpp"
#include "specs.hpp"

using namespace fts::protocol;
using namespace fts::protocol::wire;

namespace {

// ---- valid values of each kind: v = 0 low edge, 1 high edge, 2 in between ------------

template <class T>
T sample(const Int<T>& k, int v) {
  return static_cast<T>(v == 0 ? k.lo : v == 1 ? k.hi : k.lo + (k.hi - k.lo) / 3);
}
inline bool sample(const Bool&, int v) { return v == 1; }
inline bool sample(const Bit&, int v) { return v == 1; }
inline double sample(const Num& k, int v) { return v == 0 ? k.lo : v == 1 ? k.hi : k.lo + (k.hi - k.lo) / 3; }
inline std::string sample(const Text& k, int v) {
  return v == 0 ? std::string(k.min, 'a') : v == 1 ? std::string(k.max, '~') : std::string(k.min, 'b') + " ~";
}
inline std::string sample(const AnyText& k, int v) {
  return v == 0 ? std::string() : v == 1 ? std::string(k.max, '\x07') : std::string("ann");
}
inline std::string sample(const Hex& k, int v) {
  if (v == 0 && !k.required) return "";
  return std::string(k.digits, v == 1 ? 'f' : '0');
}
inline char sample(const Key&, int v) { return v == 0 ? 'm' : v == 1 ? '~' : char{0}; }
template <class E, std::size_t N>
E sample(const Named<E, N>&, int v) {
  return static_cast<E>(v == 0 ? 0 : v == 1 ? N - 1 : N / 2);
}
template <class E, std::size_t N>
E sample(const OpenNamed<E, N>&, int v) {
  return static_cast<E>(v == 0 ? 0 : v == 1 ? N - 1 : N / 2);
}
template <class T, std::size_t N, class K>
std::array<T, N> sample(const Fixed<T, N, K>& k, int v) {
  std::array<T, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = sample(k.kind, (v + static_cast<int>(i)) % 3);
  return out;
}
template <class K>
auto sample(const Tolerant<K>& k, int v) {
  return sample(k.kind, v);
}
// Ball entries have tests of their own (test_snapshot_delta.cpp): none here.
inline std::vector<BallEntry> sample(const FullBalls&, int) { return {}; }
inline std::vector<BallEntry> sample(const Motions&, int) { return {}; }

template <class M, class Table>
M fill(const Table& table, int v);
template <class M, class Table>
M sample(const RowOf<M, Table>& k, int v);
template <class M, class Table>
M sample(const MapOf<M, Table>& k, int v);

template <class T, class K>
std::vector<T> sample(const List<T, K>& k, int v) {
  if (v == 0) return {};
  return {sample(k.kind, v), sample(k.kind, (v + 1) % 3)};
}
template <class M, class Table>
M sample(const RowOf<M, Table>& k, int v) {
  return fill<M>(*k.table, v);
}
template <class M, class Table>
M sample(const MapOf<M, Table>& k, int v) {
  return fill<M>(*k.table, v);
}

template <class M, class Table>
M fill(const Table& table, int v) {
  M m{};
  std::apply([&](const auto&... f) { ((f.of(m) = sample(f.kind, v)), ...); }, table);
  return m;
}

// The cross-field rules of a snap (tables.hpp check()) hold for the generated values.
template <class M>
void make_consistent(M&, int) {}
template <>
void make_consistent(SnapshotMsg& m, int v) {
  m.tick = 1000;
  m.base = v == 0 ? std::nullopt : std::optional<std::uint32_t>{999};
  m.part = 0;
  m.parts = 1;
}

template <class M>
M generated(int v) {
  M m = fill<M>(Spec<M>::fields(), v);
  make_consistent(m, v);
  return m;
}

// ---- values just outside a kind's range (with the reason they are refused) -----------

template <class T>
using Bad = std::vector<T>;

template <class T>
Bad<T> outside(const Int<T>& k) {
  using U = std::conditional_t<std::is_enum_v<T>, std::underlying_type<T>, std::type_identity<T>>::type;
  Bad<T> out;
  if (k.hi < static_cast<std::int64_t>(std::numeric_limits<U>::max())) out.push_back(static_cast<T>(k.hi + 1));
  if (k.lo > static_cast<std::int64_t>(std::numeric_limits<U>::min())) out.push_back(static_cast<T>(k.lo - 1));
  return out;
}
inline Bad<double> outside(const Num& k) { return {k.hi * 2 + 1, k.lo - 1}; }
inline Bad<std::string> outside(const Text& k) {
  Bad<std::string> out{std::string(k.max + 1, 'a'), "tab\there"};
  if (k.min > 0) out.push_back(std::string(k.min - 1, 'a'));
  return out;
}
inline Bad<std::string> outside(const AnyText& k) { return {std::string(k.max + 1, 'a')}; }
inline Bad<std::string> outside(const Hex& k) {
  Bad<std::string> out{std::string(k.digits + 1, 'a'), std::string(k.digits, 'A'), std::string(k.digits, 'g')};
  if (k.required) out.push_back("");
  return out;
}
template <class K>
Bad<int> outside(const K&) {  // every other kind: nothing outside that can be written
  return {};
}
template <class K>
auto outside(const Tolerant<K>& k) {
  return outside(k.kind);
}
template <class K>
struct is_tolerant : std::false_type {};
template <class K>
struct is_tolerant<Tolerant<K>> : std::true_type {};

Decoded<std::vector<Message>> round_trip(const Message& m, Encoding enc) {
  return decode_payload(enc, encode_payload(enc, {m}));
}

const char* name_of(Encoding enc) { return enc == Encoding::json ? "json" : "msgpack"; }

template <class M>
void check_round_trips() {
  for (int v = 0; v < 3; ++v) {
    const Message m = generated<M>(v);
    for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
      INFO(Spec<M>::type << " variant " << v << " " << name_of(enc) << " " << to_json_text({m}));
      auto d = round_trip(m, enc);
      REQUIRE(d.ok());
      REQUIRE(d->size() == 1);
      CHECK(d->at(0) == m);
      CHECK(payload_bytes(enc, {m}) == encode_payload(enc, {m}).size());
    }
  }
}

// Any key of the message given twice ("t", each field, an unknown one) is garbage in both
// encodings, and so is a bin under a key the message does not know (PROTOCOL.md 3).
template <class M>
void check_strict(const M& good) {
  const nlohmann::json j = nlohmann::json::parse(to_json_text({good}));
  std::vector<std::string> twice{"t", "zz_unknown"};
  for (const auto& [key, value] : j[0].items()) twice.push_back(key);
  for (const auto& key : twice) {
    const std::string value = j[0].contains(key) ? j[0][key].dump() : "1";
    std::string text = j.dump();
    text.insert(text.size() - 2, "," + nlohmann::json(key).dump() + ":" + value);
    if (!j[0].contains(key)) text.insert(text.size() - 2, "," + nlohmann::json(key).dump() + ":" + value);
    INFO(Spec<M>::type << ", " << key << " twice: " << text);
    const std::span bytes(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
    auto in_json = decode_payload(Encoding::json, bytes);
    REQUIRE_FALSE(in_json.ok());
    CHECK(in_json.error() == Reject::garbage);
    std::vector<std::uint8_t> packed;  // the same map in MessagePack, both keys kept
    Reject why{};
    REQUIRE(json_to_msgpack(bytes, packed, why));
    auto in_msgpack = decode_payload(Encoding::msgpack, packed);
    REQUIRE_FALSE(in_msgpack.ok());
    CHECK(in_msgpack.error() == Reject::garbage);
  }
  for (const char* key : {"zz_bin", "mv"}) {
    if (Spec<M>::type == std::string_view("snap") && key == std::string_view("mv")) continue;  // its own
    for (bool nested : {false, true}) {
      nlohmann::json with = j;
      const auto bin = nlohmann::json::binary({1, 2, 3});
      with[0][key] = nested ? nlohmann::json::array({bin}) : bin;
      INFO(Spec<M>::type << " with a bin under " << key << (nested ? " in an array" : ""));
      auto d = decode_payload(Encoding::msgpack, nlohmann::json::to_msgpack(with));
      REQUIRE_FALSE(d.ok());
      CHECK(d.error() == Reject::garbage);
    }
  }
}

template <class M>
void check_rejections() {
  const M good = generated<M>(2);
  std::apply(
      [&](const auto&... f) {
        [[maybe_unused]] auto one = [&](const auto& field) {
          for (const auto& bad : outside(field.kind)) {
            if constexpr (std::is_assignable_v<decltype(field.of(std::declval<M&>())), decltype(bad)>) {
              M m = good;
              field.of(m) = bad;
              for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
                INFO(Spec<M>::type << "." << field.key << " " << name_of(enc) << " " << to_json_text({m}));
                auto d = round_trip(m, enc);
                if constexpr (is_tolerant<std::decay_t<decltype(field.kind)>>::value) {
                  // A tolerant field costs the message nothing but itself: the message
                  // reads, the field at its default, its key noted (PROTOCOL.md 4.6).
                  REQUIRE(d.ok());
                  M want = good;
                  field.of(want) = {};
                  if constexpr (requires { want.fault; }) want.fault = std::string(field.key);
                  CHECK(d->at(0) == Message{want});
                } else {
                  REQUIRE_FALSE(d.ok());
                  CHECK(d.error() == Reject::out_of_range);
                }
              }
            }
          }
          // A required field left out: garbage. Any unknown key: ignored.
          nlohmann::json j = nlohmann::json::parse(to_json_text({good}));
          if (field.presence == Presence::required) {
            j[0].erase(std::string(field.key));
            const std::string text = j.dump();
            INFO(Spec<M>::type << " without " << field.key << ": " << text);
            auto d = decode_payload(Encoding::json, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
            REQUIRE_FALSE(d.ok());
            CHECK(d.error() == Reject::garbage);
          }
        };
        (one(f), ...);
      },
      Spec<M>::fields());
  nlohmann::json j = nlohmann::json::parse(to_json_text({good}));
  j[0]["zz_unknown"] = {1, {{"deep", true}}};
  const auto packed = nlohmann::json::to_msgpack(j);
  auto d = decode_payload(Encoding::msgpack, packed);
  INFO(Spec<M>::type << " with an unknown key");
  REQUIRE(d.ok());
  CHECK(d->at(0) == Message{good});
  check_strict<M>(good);
}

template <std::size_t... I>
void for_every_message(std::index_sequence<I...>) {
  (check_round_trips<std::variant_alternative_t<I, Message>>(), ...);
  (check_rejections<std::variant_alternative_t<I, Message>>(), ...);
}

}  // namespace

TEST_CASE("Wire tables (generated): every field of every message round-trips, and refuses what is outside",
          "[protocol][wire][generated]") {
  for_every_message(std::make_index_sequence<std::variant_size_v<Message>>{});
}

TEST_CASE("Wire tables (generated): every message type has a table and a distinct name", "[protocol][wire][generated]") {
  std::set<std::string_view> names;
  std::size_t count = 0;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    ((names.insert(Spec<std::variant_alternative_t<I, Message>>::type), ++count), ...);
  }(std::make_index_sequence<std::variant_size_v<Message>>{});
  CHECK(names.size() == count);
  for (const auto& m : std::vector<Message>{Hello{}, Ping{}, Chat{}})
    CHECK(names.count(message_type(m)) == 1);
}
