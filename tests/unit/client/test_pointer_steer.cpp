// Mouse steering arrives and stops (issue 26: the pointer ran the ball off the edge). The
// ball here moves by the game's rules for one ball (README "Where the rules left room":
// thrust a on an axis only while that component is below vmax, friction 0.991 per 10 ms
// tick), stepped by hand at 100 Hz; the client steers at 30 frames a second from a view
// 80 ms old, as a snapshot is on a real link.
#include <catch2/catch.hpp>

#include <cmath>
#include <deque>

#include "ui/pointer_steer.hpp"

using namespace fts::client;

namespace {

constexpr double kW = 500, kH = 300, kDt = 0.01;

struct Run {
  bool fell = false;
  double max_out = 0;  // the farthest the centre came past the aim's inset (u)
  int frames_active = 0;
  SteerBall last;
};

// Starts at (x, y) with velocity (vx, vy), aims at (ax, ay) and steps `seconds`.
Run run(double x, double y, double vx, double vy, double ax, double ay, double seconds, PointerSteering& steer) {
  SteerBall b{7, x, y, vx, vy, 16, 200, 178.5};
  std::deque<SteerBall> seen;  // what the client sees: the state 8 ticks ago
  steer.aim(ax, ay, true);
  Steer thrust;
  Run r;
  for (int tick = 0; tick < static_cast<int>(seconds / kDt); ++tick) {
    seen.push_back(b);
    if (seen.size() > 8) seen.pop_front();
    if (tick % 3 == 0) {  // a frame of the client
      thrust = steer.update(&seen.front(), kW, kH, 0.08);
      if (steer.active()) ++r.frames_active;
    }
    const auto axis = [](double& v, int t, double a, double vmax) {
      if (t != 0 && std::fabs(v) < vmax) v += t * a * kDt;
      v *= 0.991;
      if (t == 0 && std::fabs(v) < 1.0) v = 0;
    };
    axis(b.vx, thrust.x, b.accel, b.vmax);
    axis(b.vy, thrust.y, b.accel, b.vmax);
    b.x += b.vx * kDt;
    b.y += b.vy * kDt;
    if (b.x < 0 || b.x > kW || b.y < 0 || b.y > kH) r.fell = true;
  }
  r.last = b;
  return r;
}

}  // namespace

TEST_CASE("Mouse steering: the ball arrives at the pointer, steering ends, never off the edge",
          "[client][mouse]") {
  // Far across the platform to each edge and corner, and from full speed toward an edge.
  struct Case {
    double x, y, vx, vy, ax, ay;
  };
  const Case cases[] = {{250, 150, 0, 0, 250, 296},  {250, 150, 0, 0, 250, 2},   {250, 150, 0, 0, 2, 150},
                        {250, 150, 0, 0, 498, 150},  {30, 30, 0, 0, 495, 295},   {470, 270, 0, 0, 3, 3},
                        {250, 150, 0, 178, 250, 290}, {100, 150, 178, 0, 480, 150}, {250, 100, 0, 0, 250, 280}};
  for (const Case& c : cases) {
    INFO("from (" << c.x << ", " << c.y << ") v (" << c.vx << ", " << c.vy << ") to (" << c.ax << ", " << c.ay << ")");
    PointerSteering steer;
    const Run r = run(c.x, c.y, c.vx, c.vy, c.ax, c.ay, 12, steer);
    CHECK_FALSE(r.fell);
    CHECK_FALSE(steer.active());  // it ended by itself...
    CHECK(std::string(steer.ended_because()) == "arrived");
    // ...at the aim, kept a radius and a margin inside the platform.
    const double inset = 16 + 8;
    CHECK(std::fabs(r.last.x - std::clamp(c.ax, inset, kW - inset)) < 12);
    CHECK(std::fabs(r.last.y - std::clamp(c.ay, inset, kH - inset)) < 12);
    CHECK(std::fabs(r.last.vx) < 13);
    CHECK(std::fabs(r.last.vy) < 13);
  }
}

TEST_CASE("Mouse steering: the old rule (thrust until within a cell) coasts off the top edge", "[client][mouse]") {
  // What the client did before issue 26, for the record: toward the pointer while farther
  // than a cell (about 6 u), then let go. From the centre to a pointer 4 u under the top
  // edge the ball is at vmax when it gets there and coasts off.
  SteerBall b{7, 250, 150, 0, 0, 16, 200, 178.5};
  bool fell = false;
  for (int tick = 0; tick < 1000 && !fell; ++tick) {
    const Steer t = steer_toward(b.x, b.y, 250, 296, 6);
    if (t.y != 0 && std::fabs(b.vy) < b.vmax) b.vy += t.y * b.accel * kDt;
    b.vy *= 0.991;
    b.y += b.vy * kDt;
    fell = b.y > kH;
  }
  CHECK(fell);
  PointerSteering steer;
  CHECK_FALSE(run(250, 150, 0, 0, 250, 296, 10, steer).fell);
}

TEST_CASE("Mouse steering ends with a new ball, off the platform, and on stop()", "[client][mouse]") {
  PointerSteering steer;
  steer.aim(400, 200, true);
  SteerBall b{7, 100, 100, 0, 0, 16, 200, 178.5};
  CHECK(steer.update(&b, kW, kH, 0) == Steer{1, 1});
  b.id = 9;  // fell and respawned: another ball
  CHECK(steer.update(&b, kW, kH, 0) == Steer{});
  CHECK_FALSE(steer.active());
  CHECK(std::string(steer.ended_because()) == "new ball");

  steer.aim(400, 200, true);
  CHECK(steer.update(nullptr, kW, kH, 0) == Steer{});  // no ball on the platform
  CHECK_FALSE(steer.active());

  steer.aim(400, 200, true);
  CHECK(steer.active());
  steer.aim(600, 200, false);  // the pointer left the platform
  CHECK_FALSE(steer.active());
  CHECK(std::string(steer.ended_because()) == "left the platform");
  CHECK(steer.update(&b, kW, kH, 0) == Steer{});

  steer.aim(400, 200, true);
  steer.stop();  // the window lost the focus, or a key steers
  CHECK(steer.update(&b, kW, kH, 0) == Steer{});
}

TEST_CASE("Focus reports decode (xterm mode 1004)", "[client][keys][mouse]") {
  KeyDecoder d;
  const auto events = d.feed("\x1b[O\x1b[I");
  REQUIRE(events.size() == 2);
  CHECK(events[0].key == Key::focus_out);
  CHECK(events[1].key == Key::focus_in);
  CHECK(action_of(events[0], fts::protocol::Phase::play).kind == ActionKind::none);
}
