// The fixed tick clock: exact schedule, bounded catch-up, skipped ticks counted.
#include <catch2/catch.hpp>

#include "app/tick_clock.hpp"

using fts::server::TickClock;

TEST_CASE("Tick clock: ticks fall due on an exact integer schedule", "[server][tick]") {
  TickClock c(100, 5);
  c.start(1'000'000'000);
  CHECK(c.due(1'000'000'000) == 1);  // tick 0 is due at start
  CHECK(c.due(1'009'999'999) == 0);
  CHECK(c.due(1'010'000'000) == 1);
  CHECK(c.next_deadline_ns() == 1'020'000'000);
  // 3 Hz does not divide 1e9: no drift after many ticks.
  TickClock t(3, 5);
  t.start(0);
  std::uint64_t run = 0;
  for (std::int64_t now = 0; now <= 1'000'000'000ll * 3000; now += 1'000'000'000ll / 3 + 1) run += t.due(now);
  CHECK(run == 9000);  // ticks 0 .. 8999; tick 9000 falls due at exactly 3000 s, past the last call
  CHECK(t.skipped() == 0);
}

TEST_CASE("Tick clock: a stall runs at most the catch-up bound and counts the rest", "[server][tick]") {
  TickClock c(100, 5);
  c.start(0);
  CHECK(c.due(0) == 1);
  // 1 s late: 100 ticks due, 5 run back to back, 95 skipped.
  CHECK(c.due(1'000'000'000) == 5);
  CHECK(c.skipped() == 95);
  // The schedule moved on: the game does not run fast to make up for the stall.
  CHECK(c.due(1'000'000'000) == 0);
  CHECK(c.next_deadline_ns() == 1'010'000'000);
  CHECK(c.due(1'010'000'000) == 1);
}
