// The game loop's small stateful pieces: loss meter, event feed, input pacing.
#include <catch2/catch.hpp>

#include "net/link_meters.hpp"
#include "term/keys.hpp"

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

TEST_CASE("Event feed: after a rejoin, what happened before the welcome is not news", "[client][link]") {
  // Issue 26: "You left." right after a rejoin. The idle kick made the player leave at
  // tick 500; the new session's first snapshot still carries that event in its window.
  EventFeed feed;
  protocol::Snapshot s;
  s.events = {{1, 100, protocol::EventKind::level_started, 0, 0, 1}};
  CHECK(feed.fresh(s).size() == 1);
  feed.start_at(600);  // the rejoin's welcome
  s.events = {{1, 100, protocol::EventKind::level_started, 0, 0, 1},
              {2, 500, protocol::EventKind::player_left, 7, 0, 0},
              {3, 601, protocol::EventKind::player_joined, 7, 0, 0}};
  const auto fresh = feed.fresh(s);
  REQUIRE(fresh.size() == 1);
  CHECK(fresh[0].kind == protocol::EventKind::player_joined);
}

TEST_CASE("Typed letters outside ASCII become one '?' each, never dropped", "[client][keys]") {
  // Issue 26: "ünïcode" in the chat line came out "ncode".
  KeyDecoder d;
  std::string typed;
  for (const KeyEvent& e : d.feed("\xc3\xbc" "n" "\xc3\xaf" "code \xe2\x82\xac\xf0\x9f\x99\x82"))
    if (e.key == Key::character) typed += e.text;
    else if (e.key == Key::space) typed += ' ';
  CHECK(typed == "?n?code ??");
  // A sequence split across reads waits for its end.
  CHECK(d.feed("\xc3").empty());
  const auto rest = d.feed("\xbc");
  REQUIRE(rest.size() == 1);
  CHECK(rest[0].text == '?');
  CHECK(rest[0].ch == 0);  // no command key: buying or steering needs ASCII
}
