#include <catch2/catch.hpp>

#include "net/interpolate.hpp"
#include "net/jitter_buffer.hpp"

using namespace fts::client;
using fts::protocol::BallState;

namespace {

Snapshot snap(std::uint32_t tick, std::vector<BallState> balls) {
  Snapshot s;
  s.tick = tick;
  s.balls = std::move(balls);
  return s;
}

BallState at(std::uint32_t id, double x, double y) {
  BallState b;
  b.id = id;
  b.x = x;
  b.y = y;
  return b;
}

}  // namespace

TEST_CASE("interpolation between two snapshots", "[client][interp]") {
  const Snapshot a = snap(100, {at(1, 0, 0), at(2, 100, 100), at(3, 5, 5)});
  const Snapshot b = snap(105, {at(1, 10, 20), at(2, 100, 50), at(4, 7, 7)});
  SECTION("halfway") {
    const Snapshot m = interpolate(a, b, 0.5);
    REQUIRE(m.balls.size() == 3);
    CHECK(m.balls[0].x == Approx(5));
    CHECK(m.balls[0].y == Approx(10));
    CHECK(m.balls[1].y == Approx(75));
    CHECK(m.balls[2].id == 4);  // new in b: where b has it
    CHECK(m.balls[2].x == Approx(7));
    CHECK(m.tick == 105);
  }
  SECTION("ends and out-of-range alpha") {
    CHECK(interpolate(a, b, 0).balls[0].x == Approx(0));
    CHECK(interpolate(a, b, 1).balls[0].x == Approx(10));
    CHECK(interpolate(a, b, 7).balls[0].x == Approx(10));
    CHECK(interpolate(a, b, -1).balls[0].x == Approx(0));
    CHECK(interpolate(a, b, std::nan("")).balls[0].x == Approx(0));
  }
}

TEST_CASE("the snapshot buffer picks the pair around the render tick", "[client][interp]") {
  SnapshotBuffer buf(4);
  buf.push(snap(100, {at(1, 0, 0)}));
  buf.push(snap(105, {at(1, 10, 0)}));
  buf.push(snap(110, {at(1, 20, 0)}));
  buf.push(snap(103, {}));  // late: dropped
  CHECK(buf.size() == 3);
  Frame f = buf.sample(107.5);
  REQUIRE(f.a != nullptr);
  CHECK(f.a->tick == 105);
  CHECK(f.b->tick == 110);
  CHECK(f.alpha == Approx(0.5));
  CHECK(interpolate(*f.a, *f.b, f.alpha).balls[0].x == Approx(15));
  f = buf.sample(50);
  CHECK((f.a->tick == 100 && f.b->tick == 100));
  f = buf.sample(500);
  CHECK((f.a->tick == 110 && f.b->tick == 110));
  for (std::uint32_t t = 115; t <= 140; t += 5) buf.push(snap(t, {}));
  CHECK(buf.size() == 4);
  CHECK(buf.newest()->tick == 140);
}

TEST_CASE("the server clock follows snapshot arrivals, and a restarted server", "[client][interp]") {
  JitterBuffer j;
  j.set_rates(100, 5);
  CHECK_FALSE(j.clock().valid());
  j.on_snapshot(1000, 50'000);
  CHECK(j.clock().tick_at(50'000) == Approx(1000));
  CHECK(j.clock().tick_at(50'100) == Approx(1010));
  // A late arrival does not pull the clock back at once; an early one moves it forward.
  j.on_snapshot(1005, 50'080);  // 30 ms late
  CHECK(j.clock().tick_at(50'100) == Approx(1010).margin(0.1));
  j.on_snapshot(1020, 50'150);  // 5 ticks early
  CHECK(j.clock().tick_at(50'150) == Approx(1020));
  // An old tick, however late, moves nothing.
  j.on_snapshot(1015, 55'000);
  CHECK(j.clock().tick_at(50'150) == Approx(1020));
  // A restarted server: far below, jump; and the buffer goes on from its ticks (a lost
  // snapshot after the restart counts as one).
  j.on_snapshot(10, 56'000);
  CHECK(j.clock().tick_at(56'000) == Approx(10));
  j.on_snapshot(20, 56'100);
  CHECK(j.clock().tick_at(56'100) == Approx(20));
  CHECK(j.burst() == 1);
  // A newer tick far ahead of the clock (a server that jumped): start afresh there.
  j.on_snapshot(5000, 56'200);
  CHECK(j.clock().tick_at(56'200) == Approx(5000));
  CHECK(j.burst() == 0);
}
