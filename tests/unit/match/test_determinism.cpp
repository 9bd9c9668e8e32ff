// ARCHITECTURE.md "Determinism rules" and GAME_RULES.md "Units": same seed and inputs give
// the same hash at every tick; the tick rate changes accuracy, not the game. (A recorded
// input log replays bit-identically: unit/room/test_input_lines.cpp, with the record's
// line format.)
#include <catch2/catch.hpp>

#include "fts/sim/bot_player.hpp"
#include "match_test_util.hpp"

using namespace fts::sim;
using namespace fts::test;

namespace {

// The state hash after every tick of a match of bots.
std::vector<std::uint64_t> bot_run(std::uint64_t seed, int players, int ticks) {
  std::vector<std::uint64_t> hashes;
  MatchState s = make_match({}, seed);
  for (int t = 0; t < ticks; ++t) {
    TickInputs in;
    if (t == 0) in = joins(players);
    for (const Player& p : s.players) in.players.push_back(bot_tick(s, p.id));
    step(s, in);
    hashes.push_back(match_hash(s));
  }
  return hashes;
}

}  // namespace

TEST_CASE("Determinism: the same seed and inputs give the same state hash at every tick") {
  CHECK(bot_run(7, 4, 3000) == bot_run(7, 4, 3000));
}

TEST_CASE("Determinism: a different seed gives a different layout") {
  MatchState a = started(4, 1);
  MatchState b = started(4, 2);
  std::vector<Vec2> pa, pb;
  for (const Ball& x : a.world.balls) pa.push_back(x.pos);
  for (const Ball& x : b.world.balls) pb.push_back(x.pos);
  CHECK(pa != pb);
  CHECK(match_hash(a) != match_hash(b));
}

TEST_CASE("Units: a player's thrust covers the same ground at 50, 100 and 200 Hz") {
  std::vector<double> moved;
  for (double hz : {50.0, 100.0, 200.0}) {
    MatchConfig cfg;
    cfg.tick_rate_hz = hz;
    MatchState s = started(1, 1, cfg);
    remove_enemies(s);
    add_enemy(s, {450, 30});
    const double x0 = ball_of(s, 1).pos.x;
    TickInputs in;
    in.players.push_back({1, {1, 0, false}, {}});
    run(s, static_cast<int>(hz * 1.5), in);  // 1.5 s of thrust
    run(s, static_cast<int>(hz * 0.5));      // 0.5 s of coasting
    moved.push_back(ball_of(s, 1).pos.x - x0);
  }
  INFO("50 Hz " << moved[0] << " u, 100 Hz " << moved[1] << " u, 200 Hz " << moved[2] << " u");
  CHECK(moved[1] > 150.0);
  CHECK(moved[0] == Approx(moved[1]).epsilon(0.03));
  CHECK(moved[2] == Approx(moved[1]).epsilon(0.03));
}

TEST_CASE("Units: respawn, shop time-out and rocket cooldown are in seconds") {
  MatchConfig cfg;
  cfg.tick_rate_hz = 50;
  CHECK(ticks_for(cfg, cfg.respawn_delay_s) == 100);
  CHECK(ticks_for(cfg, cfg.shop_timeout_s) == 1500);
  cfg.tick_rate_hz = 200;
  CHECK(ticks_for(cfg, cfg.rocket_cooldown_s) == 200);
  CHECK(ticks_for(cfg, cfg.credit_chain_s) == 1000);
}
