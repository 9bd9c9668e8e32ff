// Prediction of collisions (issue 37), time stepped by hand: the own ball driven into an
// enemy (a still one, and one thrusting toward it) is predicted from a snapshot taken
// before the contact; with the balls near it stepped too, the predicted ball after the
// contact is where the server's step puts it, within a small tolerance. The own ball
// alone (the prediction before) misses by more than that: it passes through the enemy.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "fts/room/snapshot_build.hpp"
#include "fts/sim/match.hpp"
#include "fts/sim/match_view.hpp"
#include "net/net_timing.hpp"
#include "predict/prediction.hpp"
#include "prediction_match.hpp"

using namespace fts;
using namespace fts::client;
using namespace fts::client::test;

namespace {

// The tolerance of a predicted contact: the base is quantized (1/16 u, 1/16 u/s), so the
// contact comes a little earlier or later; the rest is the same arithmetic.
constexpr double kToleranceU = 0.5;

sim::Ball& the_enemy(sim::MatchState& s) {
  for (auto& b : s.world.balls)
    if (s.bodies.at(b.id).kind == sim::BodyKind::enemy) return b;
  FAIL("no enemy");
  return s.world.balls.front();
}

double gap(sim::MatchState& s) {
  const auto& a = own(s);
  const auto& e = the_enemy(s);
  return std::hypot(a.pos.x - e.pos.x, a.pos.y - e.pos.y) - a.radius - e.radius;
}

struct Outcome {
  double worst_after_contact = 0;  // largest miss at the ticks after the first contact
  double worst_before = 0;         // ...before it
  bool contact = false;
};

// From now, the player holds right for `ticks`; the predictor, given the snapshots fed to
// it before, and the same input from `t_input`, is compared with the server at each tick.
Outcome follow(sim::MatchState s, OwnBallPredictor p, std::int64_t t_input, int ticks) {
  p.input(t_input, 1, 0);
  Outcome o;
  double last_gap = gap(s);
  for (int i = 0; i < ticks; ++i) {
    sim::step(s, move(1, 0));
    // Touching, or moving apart again (a bounce inside the tick): the contact has been.
    o.contact = o.contact || gap(s) < 0.5 || gap(s) > last_gap;
    last_gap = gap(s);
    const auto at = p.at(static_cast<double>(s.tick), 1000);
    REQUIRE(at.has_value());
    const double miss = std::hypot(at->x - own(s).pos.x, at->y - own(s).pos.y);
    (o.contact ? o.worst_after_contact : o.worst_before) = std::max(o.contact ? o.worst_after_contact : o.worst_before, miss);
  }
  return o;
}

PredictionTuning own_only() {
  PredictionTuning t;
  t.others = false;
  return t;
}

}  // namespace

TEST_CASE("Prediction of contacts: the own ball driven into a still enemy bounces where the server's does",
          "[client][predict][contact]") {
  auto s = playing_alone();  // level 1: one still enemy at the centre, the player left of it
  const std::int64_t t0 = s.tick;
  while (gap(s) > 45) sim::step(s, move(1, 0));  // about a quarter second before the contact
  const auto base = snapshot_of(s);
  OwnBallPredictor with_others(s.cfg), alone(s.cfg, own_only());
  with_others.on_snapshot(base, 1, base.tick, 1000);
  alone.on_snapshot(base, 1, base.tick, 1000);
  CHECK(with_others.others_stepped() == 1);
  CHECK(alone.others_stepped() == 0);
  const Outcome now = follow(s, with_others, t0, 45);
  const Outcome before = follow(s, alone, t0, 45);
  REQUIRE(now.contact);
  INFO("with others " << now.worst_after_contact << " u, alone " << before.worst_after_contact << " u");
  CHECK(now.worst_before < 0.1);
  CHECK(now.worst_after_contact < kToleranceU);
  CHECK(before.worst_after_contact > kToleranceU);  // the test's teeth: the old prediction misses
  // And the enemy is drawn where the server has it after the hit.
  auto after = s;
  for (int i = 0; i < 45; ++i) sim::step(after, move(1, 0));
  with_others.input(t0, 1, 0);
  const auto others = with_others.others_at(after.tick);
  REQUIRE(others.size() == 1);
  CHECK(std::hypot(others[0].x - the_enemy(after).pos.x, others[0].y - the_enemy(after).pos.y) < kToleranceU);
  CHECK(std::fabs(the_enemy(after).vel.x) > 1);  // it was hit
}

TEST_CASE("Prediction of contacts: an enemy thrusting toward the own ball is met where the server meets it",
          "[client][predict][contact]") {
  auto s = playing_alone();
  // Level 2's wanderer, heading left and down at the player (its goal far down-left):
  // the client sees neither its role nor its goal, only its velocity in two snapshots.
  s.level = 2;
  sim::Ball& e = the_enemy(s);
  sim::Body& body = s.bodies.at(e.id);
  sim::Rng scratch(0);
  body.spec = sim::enemy_spec(2, 0, scratch, s.cfg);
  body.spec.role = sim::EnemyRole::wanderer;
  // A wanderer thrusts on both axes at once, so it comes diagonally: from above, it meets
  // the player's row about where it meets the player.
  body.goal = {0.0, own(s).pos.y - 100};
  e.pos.y = own(s).pos.y + 50;
  e.mass = body.spec.mass;
  e.radius = body.spec.radius_u;
  REQUIRE(body.spec.accel_u_per_s2 > 50);
  const std::int64_t t0 = s.tick;
  OwnBallPredictor with_others(s.cfg), alone(s.cfg, own_only());
  while (gap(s) > 60) sim::step(s, move(1, 0));
  const auto first = snapshot_of(s);
  for (int i = 0; i < 5; ++i) sim::step(s, move(1, 0));  // the next snapshot, 5 ticks later (20 Hz)
  const auto base = snapshot_of(s);
  REQUIRE(gap(s) > 30);
  for (auto* p : {&with_others, &alone}) {
    p->input(t0, 1, 0);
    p->on_snapshot(first, 1, first.tick, 900);
    p->on_snapshot(base, 1, base.tick, 1000);
  }
  const Outcome now = follow(s, with_others, t0, 50);
  const Outcome before = follow(s, alone, t0, 50);
  REQUIRE(now.contact);
  INFO("with others " << now.worst_after_contact << " u, alone " << before.worst_after_contact << " u");
  CHECK(now.worst_before < 0.1);
  CHECK(now.worst_after_contact < kToleranceU);
  CHECK(before.worst_after_contact > kToleranceU);
  // Without the fitted thrust (the enemy coasting) the contact comes later: the held
  // direction is what makes it match.
  PredictionTuning no_fit;
  OwnBallPredictor coasting(s.cfg, no_fit);
  coasting.input(t0, 1, 0);
  auto still = base;
  still.level = 1;  // level 1's enemies do not thrust: the prediction lets it coast
  coasting.on_snapshot(still, 1, still.tick, 1000);
  const Outcome coast = follow(s, coasting, t0, 50);
  INFO("coasting " << coast.worst_after_contact << " u");
  CHECK(coast.worst_after_contact > now.worst_after_contact);
}

TEST_CASE("Prediction of contacts: only the balls near the own ball are stepped, at most max_others",
          "[client][predict][contact]") {
  auto s = playing_alone();
  auto snap = snapshot_of(s);
  const protocol::BallState* mine = nullptr;
  for (const auto& b : snap.balls)
    if (b.owner == 1 && b.kind == protocol::BallKind::player) mine = &b;
  REQUIRE(mine != nullptr);
  const protocol::BallState me = *mine;
  // Twenty enemies in a row to the right of ours, their edges 5, 45, 85, ... u from ours.
  snap.balls.erase(std::remove_if(snap.balls.begin(), snap.balls.end(), [&](const auto& b) { return b.id != me.id; }),
                   snap.balls.end());
  for (std::uint32_t i = 0; i < 20; ++i) {
    protocol::BallState b;
    b.id = 1000 + i;
    b.radius = 10;
    b.mass = 30;
    b.x = me.x + me.radius + 15 + 40.0 * i;
    b.y = me.y;
    snap.balls.push_back(b);
  }
  PredictionTuning t;
  t.near_gap_u = 120;
  t.max_others = 12;
  OwnBallPredictor p(s.cfg, t);
  p.on_snapshot(snap, 1, snap.tick, 0);
  CHECK(p.others_stepped() == 3);  // 5, 45 and 85 u away; 125 is beyond the gap
  t.near_gap_u = 10000;
  OwnBallPredictor capped(s.cfg, t);
  capped.on_snapshot(snap, 1, snap.tick, 0);
  CHECK(capped.others_stepped() == 12);
  const auto others = capped.others_at(snap.tick);
  REQUIRE(others.size() == 12);
  CHECK(others.back().id == 1011);  // the nearest twelve
}

TEST_CASE("Prediction of contacts: a predicted ball is drawn in the own ball's time near it, mixed farther out",
          "[client][predict][contact]") {
  protocol::BallState me;
  me.id = 1;
  me.radius = 10;
  protocol::Snapshot s;
  std::vector<protocol::BallState> near;
  for (std::uint32_t i = 0; i < 3; ++i) {
    protocol::BallState b;  // drawn (remote time) at x, predicted 8 u to the right
    b.id = 10 + i;
    b.radius = 10;
    b.x = 20.0 + 40.0 * i + 50.0 * i * i;  // predicted edges 8, 98, 288 u from ours
    s.balls.push_back(b);
    b.x += 8;
    near.push_back(b);
  }
  place_near_balls(s, near, me, 60, 120);
  CHECK(s.balls[0].x == Approx(28));        // within 60 u: the prediction
  CHECK(s.balls[1].x == Approx(110 + (120.0 - 98.0) / 60.0 * 8));  // between: a mix
  CHECK(s.balls[2].x == Approx(300));       // beyond 120 u: as the remote balls are drawn
}
