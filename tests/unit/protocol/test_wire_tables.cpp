// The field-table codec (issue 14): direct MessagePack and JSON writers and readers,
// messages written by other writers (keys in any order), sizes without encoding, the
// table delta. (Generated per-field tests: test_wire_generated.cpp.)
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

}  // namespace

TEST_CASE("Wire tables: every message round-trips in both encodings", "[protocol][wire]") {
  auto messages = test::all_messages();
  for (auto& m : snapshot_messages()) messages.push_back(m);
  for (auto enc : {Encoding::json, Encoding::msgpack}) {
    for (const auto& m : messages) {
      INFO(message_type(m) << " " << (enc == Encoding::json ? "json" : "msgpack"));
      Header h;
      h.encoding = enc;
      auto again = decode_datagram(encode_datagram(h, {m}));
      REQUIRE(again.ok());
      CHECK(again->messages.at(0) == m);
    }
  }
}

TEST_CASE("Wire tables: messages from another writer (keys sorted, \"t\" last) decode the same",
          "[protocol][wire]") {
  // What nlohmann's writer made of them before the tables (PROTOCOL.md 12; the challenge of version 3 with its key):
  // an independent client may order keys any way.
  const std::vector<std::pair<std::string, Message>> vectors = {
      {R"([{"cookie":"","name":"ann","nonce":"5eed0fa11c0ffee5","pad":"..","t":"hello","token":""}])",
       Hello{"ann", "", "", "..", "5eed0fa11c0ffee5"}},
      {R"([{"cookie":"00000000000003e83c15b96815ccf35a8bb078310802c3e0",)"
       R"("key":"cbf675d41f5be72261a95fc8d20be95cba50466d152bdb04791f6991effc1f49","t":"challenge"}])",
       Challenge{"00000000000003e83c15b96815ccf35a8bb078310802c3e0",
                 "cbf675d41f5be72261a95fc8d20be95cba50466d152bdb04791f6991effc1f49"}},
      {R"([{"arena_height_u":300.0,"arena_width_u":500.0,"bank_interest_factor":1.1,"frame_s":0.02,)"
       R"("input_redundancy":3,"max_players":8,"multiplier_upgrade_factor":1.1,"player_id":1,)"
       R"("reconnect_window_ms":60000,"reconnected":false,"server_tick":0,"snapshot_rate_hz":20,"t":"welcome",)"
       R"("tick_rate_hz":100,"timeout_ms":10000,"token":"bcf8ef0b804a8357ee42dd8334a3619d"}])",
       [] {  // a server from before issue 36: no model, sub-steps or friction; they read as defaults
         Welcome w{1, "bcf8ef0b804a8357ee42dd8334a3619d", 20, 8, 10000, 60000, 3, 0, false};
         w.match.frame_s = 0.02;
         return w;
       }()},
      {R"([{"item":"m","op":"buy","rid":1,"t":"cmd"}])", Command{1, CommandOp::buy, 'm', {}, {}}},
      {R"([{"cmd":1,"code":"ok","msg":"bought mass: 41 -> 42","ok":true,"rid":1,"t":"result"}])",
       Result{1, 1, true, "ok", "bought mass: 41 -> 42"}},
      {R"([{"from":0,"name":"host","rid":2,"t":"chat","text":"bye"}])", Chat{2, 0, "host", "bye"}},
      {R"([{"ack":205,"f":[[1,1,0,0]],"t":"input"}])", Input{205, {{1, 1, 0, false}}}},
      {R"([{"reason":"quit","t":"bye"}])", Bye{"quit"}},
      {R"([{"code":"full","msg":"the server is full","t":"error"}])", Error{"full", "the server is full"}},
      {R"([ { "t" : "ping" } ])", Ping{}},
  };
  for (const auto& [text, m] : vectors) {
    INFO(text);
    auto d = decode_payload(Encoding::json, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    REQUIRE(d.ok());
    REQUIRE(d->size() == 1);
    CHECK(d->at(0) == m);
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

TEST_CASE("Wire tables: a motion bin that ends inside a code is garbage (regression: fuzz, overflow)",
          "[protocol][wire][reject]") {
  // Found by .ci/fuzz.sh: "mv" is a 5-byte bin whose last code runs past its end. The
  // bits that ran out read as 0 - 2^k, and the id sum overflowed (UBSan).
  static const char kBytes[] =
      "\x91\x8b\xa1t\xa4snap\xa4tick\x05\xa4" "base\x04\xa2zzd\xa4part\x00\xa5parts\x01\xa5phase\xa4play\xa5level\x01"
      "\xa5" "balds\x90\xa2mv\xc4\x05\x90has\x05\xa4" "baseers\x90";
  const std::vector<std::uint8_t> payload(kBytes, kBytes + sizeof(kBytes) - 1);
  auto d = decode_payload(Encoding::msgpack, payload);
  REQUIRE_FALSE(d.ok());
  CHECK(d.error() == Reject::garbage);
}

TEST_CASE("Wire tables: a key given twice is garbage (regression: fuzz, lists merged out of order)",
          "[protocol][wire][reject]") {
  // Found by .ci/fuzz.sh: "balls" and "mv" twice each merged into one list that re-encoded
  // in another order. JSON objects and MessagePack maps alike.
  const std::string text =
      R"([{"t":"snap","tick":5,"base":4,"part":0,"parts":1,"phase":"play","level":1,"hz":100,)"
      R"("balls":[[3,1,2,3,4,1,616,0,0]],"mv":[[1,2,3,4,5]],"players":[],"balls":[[3,1,2,3,4,1,616,0,0]]}])";
  auto d = decode_payload(Encoding::json, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  REQUIRE_FALSE(d.ok());
  CHECK(d.error() == Reject::garbage);
  const std::string bye = R"([{"t":"bye","reason":"a","reason":"b"}])";
  auto b = decode_payload(Encoding::json, std::span(reinterpret_cast<const std::uint8_t*>(bye.data()), bye.size()));
  REQUIRE_FALSE(b.ok());
  CHECK(b.error() == Reject::garbage);
  // An unknown key twice too (issue 36: PROTOCOL.md 3 says a key appears at most once).
  const std::string twice = R"([{"t":"bye","zz":1,"zz":2,"reason":"a"}])";
  auto z = decode_payload(Encoding::json, std::span(reinterpret_cast<const std::uint8_t*>(twice.data()), twice.size()));
  REQUIRE_FALSE(z.ok());
  CHECK(z.error() == Reject::garbage);
}
