// The server's send path allocates nothing per datagram once warm: a connected session's
// snapshots (delta against the acknowledged base, MessagePack) go from the sender's
// buffers through the seal into a datagram whose buffers a sent one left, and the
// sender's batch swaps with the queue. Every allocation of this test program is counted
// (tests/support/count_allocations.cpp); only the server's calls are inside the window.
#include <catch2/catch.hpp>

#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "../../support/count_allocations.hpp"
#include "harness.hpp"
#include "samples.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

TEST_CASE("Server send path: no allocation per snapshot datagram once warm", "[protocol][alloc]") {
  Harness h;
  Peer& p = h.add_client(named("ann"));
  p.client.connect(h.now);
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
  h.server.take_events();
  const Snapshot s0 = test::sample_snapshot(8, 48);
  std::vector<Outgoing> batch;
  std::uint64_t counted = 0, datagrams = 0;
  std::vector<int> where;
  where.reserve(64);
  for (int tick = 0; tick < 60; ++tick) {
    // A new quantized snapshot per tick, made outside the window as the host makes it
    // once for every client.
    const auto q = std::make_shared<const Snapshot>(quantize(test::advance(s0, static_cast<std::uint32_t>(tick), 0.01)));
    const std::uint64_t before = fts::test::allocations_so_far();
    h.server.send_snapshot(1, q, h.now);
    h.server.take_datagrams(batch);
    const std::uint64_t made = fts::test::allocations_so_far() - before;
    if (made) where.push_back(tick * 1000 + static_cast<int>(made));
    if (tick >= 20) {  // warm: buffers grown, the client acknowledging
      counted += made;
      datagrams += batch.size();
    }
    for (const Outgoing& o : batch) p.client.receive(o.bytes, h.now);
    p.client.update(h.now);
    for (auto& bytes : p.client.take_datagrams()) h.server.receive(p.address, bytes, h.now);
    h.now += 10;
  }
  std::string ticks;
  for (int t : where) ticks += " " + std::to_string(t);
  INFO(counted << " allocations for " << datagrams << " datagrams; ticks that allocated:" << ticks);
  REQUIRE(datagrams >= 40);
  CHECK(counted == 0);
}

TEST_CASE("Server send path: a snapshot datagram is PROTOCOL.md's, a list holding the one part", "[protocol]") {
  // The direct path (append_snapshot_payload into the seal) must put on the wire what the
  // document describes and what the general encoder wrote before it: opened with the
  // client's keys and decoded as any payload, the datagram holds exactly one `snap`
  // message, and encoding that list again gives the same plaintext bytes.
  for (Encoding enc : {Encoding::msgpack, Encoding::json}) {
    INFO((enc == Encoding::json ? "json" : "msgpack"));
    Harness h;
    ClientConfig config = named("ann");
    config.encoding = enc;
    Peer& p = h.add_client(config);
    p.client.connect(h.now);
    REQUIRE(h.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
    h.server.take_datagrams();
    SealedChannel reader(p.client.session_keys(), SealDirection::client_to_server, SealDirection::server_to_client);
    h.server.send_snapshot(1, std::make_shared<const Snapshot>(quantize(test::sample_snapshot(8, 48))), h.now);
    const auto datagrams = h.server.take_datagrams();
    REQUIRE_FALSE(datagrams.empty());
    for (const Outgoing& o : datagrams) {
      std::vector<std::uint8_t> plain;
      const auto opened = open_sealed(reader, o.bytes, kProtocolVersion, plain);
      REQUIRE(opened.ok());
      CHECK(opened->header.encoding == enc);
      REQUIRE(opened->messages.size() == 1);
      CHECK(std::holds_alternative<SnapshotMsg>(opened->messages[0]));
      std::vector<std::uint8_t> again;
      append_payload(enc, opened->messages, again);
      CHECK(again == plain);
    }
  }
}
