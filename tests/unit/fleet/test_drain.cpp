// Drain: over when the last room ends or the grace runs out, whichever is first.
#include <catch2/catch.hpp>

#include "fleet/drain.hpp"

using fts::server::Drain;

TEST_CASE("Drain: not started, never over", "[fleet]") {
  Drain d(1000);
  CHECK_FALSE(d.active());
  CHECK_FALSE(d.over(5000, 0));
}

TEST_CASE("Drain: over when the last room ends", "[fleet]") {
  Drain d(1000);
  d.start(100);
  CHECK(d.active());
  CHECK_FALSE(d.over(200, 1));
  CHECK_FALSE(d.over(1099, 1));
  CHECK(d.over(500 + 599, 0));
  CHECK_FALSE(d.timed_out());
  CHECK(d.over_ms() == 1099u);
  CHECK(d.over(2000, 3));  // stays over
}

TEST_CASE("Drain: over when the grace runs out, rooms or not", "[fleet]") {
  Drain d(1000);
  d.start(100);
  d.start(600);  // a second drain does not move the start
  CHECK_FALSE(d.over(1099, 2));
  CHECK(d.over(1100, 2));
  CHECK(d.timed_out());
}

TEST_CASE("Drain: a grace of 0 ends at the first tick", "[fleet]") {
  Drain d(0);
  d.start(10);
  CHECK(d.over(10, 1));
}
