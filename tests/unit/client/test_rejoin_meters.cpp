// Issue 37, point 4: after a rejoin the link meters read the new session only. A player
// who came back after a minute away saw `Loss: 59.7%  Delay: 249 ms` on plain loopback,
// falling to 0.5 % only after 20 s: the minute's gap in snapshot ticks counted as lost
// snapshots and as a burst the jitter buffer bridged. Time is stepped by hand.
#include <catch2/catch.hpp>

#include <optional>

#include "net/net_timing.hpp"

using namespace fts;
using namespace fts::client;

namespace {

// Snapshots every 50 ms (every 5 ticks at 100 Hz) from `tick` at `now_ms`, for `ms`.
void clean_link(NetTiming& net, std::uint32_t& tick, std::uint64_t& now_ms, std::uint64_t ms) {
  for (const std::uint64_t end = now_ms + ms; now_ms < end; now_ms += 50, tick += 5) {
    protocol::Snapshot s;
    s.tick = tick;
    net.on_snapshot(s, 1, now_ms);
    net.remote_tick(now_ms, std::nullopt);
  }
}

}  // namespace

TEST_CASE("Link meters: a rejoin starts them afresh (no loss or delay from the time away)", "[client][link]") {
  NetTiming net(/*predict=*/false);
  protocol::Welcome w;  // 100 Hz, 20 snapshots a second
  net.on_welcome(w);
  std::uint32_t tick = 5;
  std::uint64_t now = 100'000;
  clean_link(net, tick, now, 10'000);
  CHECK(net.loss_percent() == Approx(0).margin(0.01));
  const double before_ms = net.remote_delay_ms();
  CHECK(before_ms < 120);

  // Away for 60 s while the room went on (6000 ticks), then a new session's welcome.
  tick += 6000;
  now += 60'000;
  w.reconnected = true;
  w.server_tick = tick;
  net.on_welcome(w);
  clean_link(net, tick, now, 500);  // half a second of the new session
  CHECK(net.loss_percent() == Approx(0).margin(0.01));
  CHECK(net.remote_delay_ms() < 120);
  CHECK(net.jitter_ms() < 10);
}

TEST_CASE("Link meters: loss is still measured within a session", "[client][link]") {
  NetTiming net(false);
  net.on_welcome(protocol::Welcome{});
  std::uint64_t now = 1000;
  for (std::uint32_t t = 10; t <= 2000; t += 10, now += 100) {  // every other snapshot lost
    protocol::Snapshot s;
    s.tick = t;
    net.on_snapshot(s, 1, now);
  }
  CHECK(net.loss_percent() == Approx(50).margin(1));
}
