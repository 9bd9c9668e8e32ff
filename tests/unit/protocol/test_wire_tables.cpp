// The field-table codec (issue 14): direct MessagePack and JSON writers and the direct
// reader against the nlohmann codec they replace, sizes without encoding, the table delta.
#include <catch2/catch.hpp>

#include <random>

#include "fts/protocol/codec.hpp"
#include "fts/protocol/snapshot_delta.hpp"
#include "samples.hpp"

using namespace fts::protocol;

namespace {

// The parts of a full 8-player, 48-enemy snapshot, and its 20 Hz delta: what a client gets.
std::vector<Message> snapshot_messages() {
  std::vector<Message> out;
  const Snapshot s = test::sample_snapshot(8, 48);
  for (auto& part : split_snapshot(make_snapshot_msg(s, nullptr), Encoding::json)) out.push_back(part);
  out.push_back(make_snapshot_msg(test::advance(s, 5, 0.05), &s));
  return out;
}

bool has_motion(const Message& m) {
  const auto* snap = std::get_if<SnapshotMsg>(&m);
  if (!snap) return false;
  for (const auto& b : snap->balls)
    if (!b.full) return true;
  return false;
}

}  // namespace

TEST_CASE("Wire tables: every message round-trips in both encodings", "[protocol][wire]") {
  auto messages = test::all_messages();
  for (auto& m : snapshot_messages()) messages.push_back(m);
  for (auto enc : {Encoding::json, Encoding::msgpack}) {
    for (const auto& m : messages) {
      INFO(message_type(m) << " " << (enc == Encoding::json ? "json" : "msgpack"));
      if (!has_motion(m)) {  // the old reader reads the new bytes (motion entries moved to "mv")
        auto d = legacy::decode_payload(enc, encode_payload(enc, {m}));
        REQUIRE(d.ok());
        CHECK(d->at(0) == m);
      }
      Header h;
      h.encoding = enc;
      auto again = decode_datagram(encode_datagram(h, {m}));
      REQUIRE(again.ok());
      CHECK(again->messages.at(0) == m);
    }
  }
}

TEST_CASE("Wire tables: the new reader reads what the old writer wrote", "[protocol][wire]") {
  std::vector<Message> messages;
  for (auto& m : test::all_messages())
    if (!has_motion(m)) messages.push_back(m);
  for (auto enc : {Encoding::json, Encoding::msgpack}) {
    auto d = decode_payload(enc, legacy::encode_payload(enc, messages));
    REQUIRE(d.ok());
    CHECK(*d == messages);
  }
}

TEST_CASE("Wire tables: MessagePack output has the old codec's size, deltas less", "[protocol][wire]") {
  // The same values in the same representations (only the key order differs: table
  // order here, sorted there); motion entries are packed bits now.
  for (const auto& m : snapshot_messages()) {
    const auto now = encode_payload(Encoding::msgpack, {m}).size();
    const auto before = legacy::encode_payload(Encoding::msgpack, {m}).size();
    if (has_motion(m)) CHECK(now < before);
    else CHECK(now == before);
  }
}

TEST_CASE("Wire tables: sizes without encoding equal the encoded sizes", "[protocol][wire]") {
  auto messages = test::all_messages();
  for (auto& m : snapshot_messages()) messages.push_back(m);
  for (auto enc : {Encoding::json, Encoding::msgpack}) {
    for (const auto& m : messages) {
      INFO(message_type(m));
      CHECK(payload_bytes(enc, {m}) == encode_payload(enc, {m}).size());
    }
    CHECK(payload_bytes(enc, messages) == encode_payload(enc, messages).size());
  }
}

TEST_CASE("Wire tables: a delta carries exactly the player fields that changed", "[protocol][wire]") {
  const Snapshot base = quantize(test::sample_snapshot(1, 0));
  // One change per PlayerState field: the delta names that field alone and rebuilds it.
  const std::vector<void (*)(PlayerState&)> changes = {
      [](PlayerState& p) { p.name = "renamed"; },       [](PlayerState& p) { p.coins += 1; },
      [](PlayerState& p) { p.lives -= 1; },             [](PlayerState& p) { p.mass += 0.5; },
      [](PlayerState& p) { p.vmax_u_per_s += 1; },      [](PlayerState& p) { p.accel_u_per_s2 += 1; },
      [](PlayerState& p) { p.multiplier *= 1.1; },      [](PlayerState& p) { p.bank = !p.bank; },
      [](PlayerState& p) { p.weapon = Weapon::rockets; }, [](PlayerState& p) { p.prices[3] += 7; },
      [](PlayerState& p) { p.ready = !p.ready; },       [](PlayerState& p) { p.alive = !p.alive; },
  };
  for (std::size_t i = 0; i < changes.size(); ++i) {
    INFO("change " << i);
    Snapshot now = base;
    now.tick += 1;
    changes[i](now.players[0]);
    const SnapshotMsg delta = make_snapshot_msg(now, &base);
    REQUIRE(delta.players.size() == 1);
    const PlayerEntry& e = delta.players[0];
    const int set = e.name.has_value() + e.coins.has_value() + e.lives.has_value() + e.mass.has_value() +
                    e.vmax_u_per_s.has_value() + e.accel_u_per_s2.has_value() + e.multiplier.has_value() +
                    e.bank.has_value() + e.weapon.has_value() + e.prices.has_value() + e.ready.has_value() +
                    e.alive.has_value();
    CHECK(set == 1);
    for (auto enc : {Encoding::json, Encoding::msgpack}) {
      auto d = decode_payload(enc, encode_payload(enc, {delta}));
      REQUIRE(d.ok());
      auto rebuilt = apply_snapshot({std::get<SnapshotMsg>(d->at(0))}, &base);
      REQUIRE(rebuilt.ok());
      CHECK(rebuilt->players == now.players);
    }
  }
  // Nothing changed: the player is not sent.
  Snapshot same = base;
  same.tick += 1;
  CHECK(make_snapshot_msg(same, &base).players.empty());
}

TEST_CASE("Wire tables: mutated MessagePack never decodes into something that re-encodes differently",
          "[protocol][wire][reject]") {
  std::mt19937 rng(14);
  const auto messages = snapshot_messages();
  const auto good = encode_payload(Encoding::msgpack, {messages[1]});
  int decoded = 0;
  for (int i = 0; i < 3000; ++i) {
    auto bytes = good;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < flips; ++k) bytes[rng() % bytes.size()] = static_cast<std::uint8_t>(rng());
    if (rng() % 4 == 0) bytes.resize(rng() % bytes.size());
    auto d = decode_payload(Encoding::msgpack, bytes);
    if (!d.ok()) continue;
    ++decoded;
    auto again = decode_payload(Encoding::msgpack, encode_payload(Encoding::msgpack, *d));
    REQUIRE(again.ok());
    CHECK(*again == *d);
  }
  CHECK(decoded > 0);  // some mutations (a changed number) still decode
}
