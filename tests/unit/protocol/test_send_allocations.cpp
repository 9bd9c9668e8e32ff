// The server's send path allocates nothing per datagram once warm: a connected session's
// snapshots (delta against the acknowledged base, MessagePack) go from the sender's
// buffers through the seal into a datagram whose buffers a sent one left, and the
// sender's batch swaps with the queue. Every allocation of this test program is counted
// (tests/support/count_allocations.cpp); only the server's calls are inside the window.
#include <catch2/catch.hpp>

#include <memory>
#include <string>
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
