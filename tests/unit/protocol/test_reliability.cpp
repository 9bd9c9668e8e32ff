// Packet acks, the reliable channel's edge cases, and hostile bytes against the endpoints.
#include <catch2/catch.hpp>

#include <deque>
#include <random>
#include <set>

#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

TEST_CASE("acks survive sequence wrap-around", "[protocol][ack]") {
  AckWindow a, b;
  std::vector<std::uint16_t> acked;
  std::uint64_t now = 0;
  std::size_t total_acked = 0;
  for (int i = 0; i < 70000; ++i) {
    Header h;
    a.stamp(h, now);
    if (h.sequence == 0) FAIL("sequence 0 sent");
    acked.clear();
    if (!b.on_receive(h, now, acked)) FAIL("refused at " << i);
    Header back;
    b.stamp(back, now);
    acked.clear();
    if (!a.on_receive(back, now + 1, acked)) FAIL("ack refused at " << i);
    total_acked += acked.size();
    now += 10;
  }
  CHECK(total_acked == 70000);  // every packet of a acknowledged exactly once
  CHECK(a.rtt_ms() == Approx(1.0));
}

TEST_CASE("each acknowledged packet is reported once, by the first header that acks it",
          "[protocol][ack]") {
  // A lossy, reordering link both ways (seeded): every header b sends back that reaches a
  // reports exactly the sequences it acknowledges that no earlier header did, whatever
  // order the headers come in (on_receive skips the bits it went through already).
  AckWindow a, b;
  std::mt19937 rng(39);
  std::deque<Header> to_b, to_a;
  std::set<std::uint16_t> reported, sent;
  std::vector<std::uint16_t> acked;
  std::uint64_t now = 0;
  auto deliver = [&](std::deque<Header>& q) {  // the oldest or (1 in 4) the second oldest
    if (q.size() > 1 && rng() % 4 == 0) std::swap(q[0], q[1]);
    Header h = q.front();
    q.pop_front();
    return h;
  };
  for (int i = 0; i < 5000; ++i, now += 10) {
    Header h;
    a.stamp(h, now);
    sent.insert(h.sequence);
    if (rng() % 10 < 7) to_b.push_back(h);
    if (to_b.size() > 2 || (!to_b.empty() && rng() % 2 == 0)) {
      acked.clear();
      b.on_receive(deliver(to_b), now, acked);
      Header back;
      b.stamp(back, now);
      if (rng() % 10 < 7) to_a.push_back(back);
    }
    if (to_a.size() > 2 || (!to_a.empty() && rng() % 2 == 0)) {
      const Header back = deliver(to_a);
      std::set<std::uint16_t> expected;
      if (back.ack != 0 && sent.count(back.ack) && !reported.count(back.ack)) expected.insert(back.ack);
      for (unsigned k = 0; k < 32; ++k) {
        const auto seq = static_cast<std::uint16_t>(back.ack - 1 - k);
        if (back.ack != 0 && (back.ack_bits >> k & 1u) && seq != 0 && !reported.count(seq)) expected.insert(seq);
      }
      acked.clear();
      if (!a.on_receive(back, now, acked)) continue;  // a duplicate or far behind: not read
      REQUIRE(std::set<std::uint16_t>(acked.begin(), acked.end()) == expected);
      REQUIRE(acked.size() == expected.size());
      reported.insert(acked.begin(), acked.end());
    }
  }
  CHECK(reported.size() > 2000);
}

TEST_CASE("an ack of a packet not sent yet does not hide its later ack", "[protocol][ack]") {
  AckWindow w;
  std::vector<std::uint16_t> acked;
  for (int i = 0; i < 5; ++i) {  // sequences 1..5 sent
    Header out;
    w.stamp(out, 0);
  }
  Header in;
  in.sequence = 1;
  in.ack = 7;  // ahead of what was sent: nothing is acknowledged
  in.ack_bits = 0x3Fu;  // 6..1
  CHECK(w.on_receive(in, 0, acked));
  const std::vector<std::uint16_t> first = acked;
  for (int i = 0; i < 3; ++i) {  // 6..8 sent now
    Header out;
    w.stamp(out, 0);
  }
  acked.clear();
  in.sequence = 2;
  in.ack = 8;
  in.ack_bits = 0x7Fu;  // 7..1
  CHECK(w.on_receive(in, 0, acked));
  CHECK(first == std::vector<std::uint16_t>{5, 4, 3, 2, 1});
  CHECK(acked == std::vector<std::uint16_t>{8, 7, 6});
}

TEST_CASE("duplicates and packets too far behind are refused", "[protocol][ack]") {
  AckWindow w;
  std::vector<std::uint16_t> acked;
  Header h;
  h.sequence = 100;
  CHECK(w.on_receive(h, 0, acked));
  CHECK_FALSE(w.on_receive(h, 0, acked));  // duplicate
  h.sequence = 90;
  CHECK(w.on_receive(h, 0, acked));        // late but inside the window
  CHECK_FALSE(w.on_receive(h, 0, acked));
  h.sequence = 60;
  CHECK_FALSE(w.on_receive(h, 0, acked));  // 40 behind
  Header out;
  w.stamp(out, 0);
  CHECK(out.ack == 100);
  CHECK(out.ack_bits == (1u << 9));        // 90 = 100 - 1 - 9
}

TEST_CASE("reliable receiver delivers in order exactly once", "[protocol][reliable]") {
  ReliableReceiver<Command> rx;
  auto cmd = [](std::uint32_t rid) { return Command{rid, CommandOp::ready, 0, {}, {}}; };
  CHECK_FALSE(rx.accept(cmd(2)));
  CHECK(rx.take().empty());
  CHECK(rx.accept(cmd(2)) == Reject::stale);
  CHECK_FALSE(rx.accept(cmd(1)));
  const auto got = rx.take();
  REQUIRE(got.size() == 2);
  CHECK(got[0].rid == 1);
  CHECK(got[1].rid == 2);
  CHECK(rx.accept(cmd(1)) == Reject::stale);
  CHECK(rx.accept(cmd(100000)) == Reject::out_of_range);
}

TEST_CASE("reliable sender resends until acknowledged", "[protocol][reliable]") {
  ReliableSender<Command> tx;
  tx.push(Command{0, CommandOp::buy, 'm', {}, {}});
  CHECK(tx.collect(1, 0, 100, 8).size() == 1);
  CHECK(tx.collect(2, 50, 100, 8).empty());  // too early to resend
  CHECK(tx.collect(3, 100, 100, 8).size() == 1);
  tx.on_acked(2);                            // the packet without it: nothing changes
  CHECK(tx.pending() == 1);
  tx.on_acked(1);                            // the first copy arrived
  CHECK(tx.pending() == 0);
  CHECK_FALSE(tx.due(1000, 100));
}

TEST_CASE("mutated datagrams never crash or change a session", "[protocol][reject][hostile]") {
  Harness h;
  Peer& p = h.add_client(ClientConfig{});
  p.client.connect(h.now);
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
  h.server.take_events();
  Snapshot s;
  s.tick = 10;
  s.balls.push_back({1, 10, 10, 1, 1, 16, 40, BallKind::player, 1});
  h.server.send_snapshot(1, s, h.now);
  h.server.send_result(1, 1, ResultCode::coins, "no", h.now);
  std::vector<std::vector<std::uint8_t>> seeds;
  for (auto& o : h.server.take_datagrams()) seeds.push_back(o.bytes);
  p.client.send_command(CommandOp::buy, 'm', h.now);
  for (auto& b : p.client.take_datagrams()) seeds.push_back(b);
  REQUIRE(seeds.size() >= 3);

  std::uint64_t r = 12345;
  auto next = [&r] { return r = r * 6364136223846793005ull + 1442695040888963407ull, r >> 33; };
  ServerEndpoint server(one_room(test_server_config(), server));
  ClientEndpoint client;
  client.connect(0);
  for (int i = 0; i < 20000; ++i) {
    auto bytes = seeds[next() % seeds.size()];
    const int edits = 1 + static_cast<int>(next() % 4);
    for (int e = 0; e < edits; ++e) {
      switch (next() % 4) {
        case 0: bytes[next() % bytes.size()] = static_cast<std::uint8_t>(next()); break;
        case 1: bytes.resize(next() % (bytes.size() + 1)); break;
        case 2: bytes.insert(bytes.begin() + static_cast<long>(next() % (bytes.size() + 1)), static_cast<std::uint8_t>(next())); break;
        default: if (bytes.size() > kHeaderBytes) bytes[kHeaderBytes + next() % (bytes.size() - kHeaderBytes)] ^= 0x20;
      }
      if (bytes.empty()) bytes.push_back(0);
    }
    server.receive("9.9.9.9:9", bytes, 1000 + i);
    client.receive(bytes, 1000 + i);
  }
  CHECK(server.sessions().empty());
  CHECK(server.take_events().empty());
  CHECK(server.rejects().total() > 10000);
}
