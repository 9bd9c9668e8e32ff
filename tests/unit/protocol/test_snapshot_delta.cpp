// Snapshot deltas: reconstruction, quantization, parts, and sizes.
#include <catch2/catch.hpp>

#include <cstdio>

#include "fts/protocol/codec.hpp"
#include "fts/protocol/snapshot_delta.hpp"
#include "samples.hpp"

using namespace fts::protocol;

namespace {

// Encodes the parts as datagrams, decodes them and feeds the receiver.
std::optional<Snapshot> transmit(const std::vector<SnapshotMsg>& parts, Encoding enc,
                                 SnapshotReceiver& rx) {
  std::optional<Snapshot> out;
  for (const auto& part : parts) {
    Header h;
    h.encoding = enc;
    const auto bytes = encode_datagram(h, {part});
    REQUIRE(bytes.size() <= kMaxDatagramBytes);
    auto d = decode_datagram(bytes);
    REQUIRE(d.ok());
    auto r = rx.accept(std::get<SnapshotMsg>(d->messages.at(0)));
    REQUIRE(r.ok());
    if (*r) out = **r;
  }
  return out;
}

}  // namespace

TEST_CASE("quantize rounds to 1/16 and sorts by id", "[protocol][snapshot]") {
  Snapshot s;
  s.balls.push_back({5, 1.03, -2.97, 0.5, 100.0 / 3, 16, 40, BallKind::enemy, 0});
  s.balls.push_back({2, 0, 0, 0, 0, 1, 1, BallKind::player, 1});
  const Snapshot q = quantize(s);
  REQUIRE(q.balls.size() == 2);
  CHECK(q.balls[0].id == 2);
  CHECK(q.balls[1].x == 1.0);
  CHECK(q.balls[1].y == -3.0);
  CHECK(q.balls[1].vy == 33.3125);
  CHECK(quantize(q) == q);
}

TEST_CASE("full and delta snapshots reconstruct the quantized state exactly", "[protocol][snapshot]") {
  for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
    CAPTURE(static_cast<int>(enc));
    SnapshotSender tx;
    SnapshotReceiver rx;
    Snapshot s = test::sample_snapshot(8, 48);
    auto got = transmit(tx.encode(s, enc), enc, rx);
    REQUIRE(got);
    CHECK(*got == quantize(s));
    for (int i = 0; i < 20; ++i) {
      tx.on_ack(rx.latest_tick());
      s = test::advance(s, 5, 0.05);
      if (i == 3) s.balls.erase(s.balls.begin() + 10);              // an enemy falls off
      if (i == 5) s.players[2].coins += 57, s.players[2].ready = true;
      if (i == 7) s.balls.push_back({900, 10, 10, 300, 0, 3, 5, BallKind::rocket, 1});
      if (i == 9) s.players.pop_back();                             // a player leaves
      if (i == 11) s.phase = Phase::shop, s.level = 8;
      if (i == 12) s.balls[0].mass = 41, s.balls[0].radius = 16;    // bought mass
      s.events.push_back({s.tick, s.tick, EventKind::rocket_fired, 1, 900, 0});
      const auto parts = tx.encode(s, enc);
      REQUIRE(!parts.empty());
      CHECK(parts[0].base.has_value());
      got = transmit(parts, enc, rx);
      REQUIRE(got);
      Snapshot expected = quantize(s);
      std::erase_if(expected.events, [&](const Event& e) { return e.tick <= *parts[0].base; });
      CHECK(*got == expected);
    }
  }
}

TEST_CASE("a delta against a snapshot the client lacks is rejected", "[protocol][snapshot]") {
  SnapshotReceiver rx;
  SnapshotMsg m = make_snapshot_msg(test::sample_snapshot(1, 1, 20), nullptr);
  m.base = 10;
  auto r = rx.accept(m);
  REQUIRE(!r.ok());
  CHECK(r.error() == Reject::unknown_base);
}

TEST_CASE("older and duplicate parts are stale", "[protocol][snapshot]") {
  SnapshotReceiver rx;
  const auto s = test::sample_snapshot(1, 2, 50);
  const auto m = make_snapshot_msg(s, nullptr);
  REQUIRE(rx.accept(m).ok());
  auto again = rx.accept(m);
  REQUIRE(!again.ok());
  CHECK(again.error() == Reject::stale);
}

TEST_CASE("every part of a large snapshot fits a datagram", "[protocol][snapshot]") {
  for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
    Snapshot s = test::sample_snapshot(8, 48);
    for (int i = 0; i < 200; ++i) s.events.push_back({static_cast<std::uint32_t>(s.tick + i), s.tick, EventKind::enemy_fell, 1, 2, 3});
    const auto parts = split_snapshot(make_snapshot_msg(s, nullptr), enc);
    REQUIRE(parts.size() >= 2);
    for (const auto& p : parts) {
      Header h;
      h.encoding = enc;
      CHECK(encode_datagram(h, {p}).size() <= kMaxDatagramBytes);
    }
  }
}

TEST_CASE("a delta of the 8-player 48-enemy level fits one MessagePack datagram", "[protocol][snapshot][sizes]") {
  SnapshotSender tx;
  SnapshotReceiver rx;
  Snapshot s = test::sample_snapshot(8, 48);
  transmit(tx.encode(s, Encoding::msgpack), Encoding::msgpack, rx);
  tx.on_ack(rx.latest_tick());
  s = test::advance(s, 5, 0.05);  // every ball moves (20 Hz snapshots)
  const auto parts = tx.encode(s, Encoding::msgpack);
  REQUIRE(parts.size() == 1);
  Header h;
  CHECK(encode_datagram(h, {parts[0]}).size() <= kMaxDatagramBytes);
}

namespace {
std::size_t datagram_bytes(const std::vector<SnapshotMsg>& parts, Encoding enc) {
  std::size_t total = 0;
  for (const auto& p : parts) {
    Header h;
    h.encoding = enc;
    total += encode_datagram(h, {p}).size();
  }
  return total;
}
}  // namespace

// Prints the table for protocol/SIZES.md: fts_protocol_tests "[.report]"
TEST_CASE("snapshot sizes report", "[.report]") {
  std::printf("| level | encoding | full: bytes (datagrams) | delta 1 tick: bytes (datagrams) | delta 5 ticks: bytes (datagrams) |\n");
  std::printf("|---|---|---|---|---|\n");
  for (auto [players, enemies] : {std::pair{1, 1}, std::pair{8, 48}}) {
    for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
      const Snapshot s = test::sample_snapshot(players, enemies);
      const auto full = split_snapshot(make_snapshot_msg(s, nullptr), enc);
      const Snapshot s1 = test::advance(s, 1, 0.01);
      const Snapshot s5 = test::advance(s, 5, 0.05);
      const auto d1 = split_snapshot(make_snapshot_msg(s1, &s), enc);
      const auto d5 = split_snapshot(make_snapshot_msg(s5, &s), enc);
      std::printf("| %d player(s), %d enemies | %s | %zu (%zu) | %zu (%zu) | %zu (%zu) |\n", players,
                  enemies, enc == Encoding::json ? "JSON" : "MessagePack", datagram_bytes(full, enc),
                  full.size(), datagram_bytes(d1, enc), d1.size(), datagram_bytes(d5, enc), d5.size());
    }
  }
  // Worst case for players: in the shop every player buys at once (balls at rest).
  for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
    const Snapshot s = test::sample_snapshot(8, 48);
    Snapshot shop = s;
    shop.tick += 5;
    for (auto& p : shop.players) {
      p.coins -= 35, p.mass += 1, p.vmax_u_per_s *= 1.05, p.accel_u_per_s2 *= 1.05;
      p.multiplier *= 1.1, p.prices[0] += 3, p.ready = true;
    }
    const auto d = split_snapshot(make_snapshot_msg(shop, &s), enc);
    std::printf("| 8 players, 48 enemies, shop: every player changed, balls still | %s | | %zu (%zu) | |\n",
                enc == Encoding::json ? "JSON" : "MessagePack", datagram_bytes(d, enc), d.size());
  }
}

TEST_CASE("the sender's history keeps the last 64 snapshots sent, a tick sent again once",
          "[protocol][snapshot]") {
  // base_for finds an acknowledged tick only while it is among the last kHistory sent
  // (a ring: each new one takes the oldest's slot); a tick sent again replaces its entry
  // and counts as the newest; on_ack takes only ticks in the history.
  constexpr std::uint32_t kHistory = static_cast<std::uint32_t>(SnapshotSender::kHistory);
  SnapshotSender tx(100000);
  auto snap = [](std::uint32_t tick) {
    auto s = std::make_shared<Snapshot>();
    s->tick = tick;
    return SharedSnapshot(std::move(s));
  };
  Snapshot later;
  later.tick = 100000;
  for (std::uint32_t t = 1; t <= 200; ++t) tx.sent(snap(t));
  tx.on_ack(136);  // 200 - 64 = 136 has left: not taken
  CHECK_FALSE(tx.acked_tick());
  tx.on_ack(137);  // the oldest held
  REQUIRE(tx.acked_tick() == 137u);
  REQUIRE(tx.base_for(later) != nullptr);
  CHECK(tx.base_for(later)->tick == 137);

  // 150 sent again: it is the newest now, so the next 63 leave 137..149 and 151..200 ...
  tx.sent(snap(150));
  for (std::uint32_t t = 201; t < 201 + kHistory - 1; ++t) tx.sent(snap(t));
  SnapshotSender probe = tx;
  probe.on_ack(150);
  CHECK(probe.acked_tick() == 150u);
  // ... and one more takes it.
  tx.sent(snap(201 + kHistory - 1));
  tx.on_ack(150);
  CHECK(tx.acked_tick() == 137u);  // 150 left; the ack stays where it was
  CHECK(tx.base_for(later) == nullptr);  // 137 left long ago

  tx.reset();
  tx.on_ack(264);
  CHECK_FALSE(tx.acked_tick());
  tx.sent(snap(300));
  tx.on_ack(300);
  CHECK(tx.acked_tick() == 300u);
}
