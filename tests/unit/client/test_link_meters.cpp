// The game loop's small stateful pieces: loss meter, event feed, input pacing.
#include <catch2/catch.hpp>

#include "ui/link_meters.hpp"

using namespace fts;
using namespace fts::client;

TEST_CASE("Loss meter: gaps in snapshot ticks count as lost snapshots", "[client][link]") {
  LossMeter m;
  CHECK(m.percent() < 0);  // nothing to judge yet
  for (std::uint32_t t = 5; t <= 100; t += 5) m.on_snapshot(t, 5);
  CHECK(m.percent() == Approx(0));
  LossMeter lossy;
  for (std::uint32_t t = 10; t <= 400; t += 10) lossy.on_snapshot(t, 5);  // every other one lost
  CHECK(lossy.percent() == Approx(50).margin(1));
}

TEST_CASE("Event feed: each event passes once, however many snapshots repeat it", "[client][link]") {
  EventFeed feed;
  protocol::Snapshot s;
  s.tick = 10;
  s.events = {{1, 8, protocol::EventKind::purchase, 1, 0, 30}, {2, 9, protocol::EventKind::level_started, 0, 0, 1}};
  CHECK(feed.fresh(s).size() == 2);
  s.tick = 15;
  // The same purchase again in the same tick is a new event: it has its own seq.
  s.events.push_back({3, 9, protocol::EventKind::purchase, 1, 0, 30});
  const auto again = feed.fresh(s);
  REQUIRE(again.size() == 1);
  CHECK(again[0].seq == 3);
  CHECK(feed.fresh(s).empty());  // the same snapshot once more: nothing new
  s.events = {{2, 9, protocol::EventKind::level_started, 0, 0, 1}};  // an old window
  CHECK(feed.fresh(s).empty());
}
