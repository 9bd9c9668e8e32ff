// The match's side of sessions (issue 11): the lobby does not wait for ever for an idle
// player, a quit takes the ball off at once without a life, keeps the progress and gives
// the seat up, and names are unique within a match.
#include <catch2/catch.hpp>

#include "match_test_util.hpp"

using namespace fts::test;

TEST_CASE("Lobby: an idle player does not hold the lobby past the time-out", "[match][lobby]") {
  MatchConfig cfg;
  cfg.lobby_timeout_s = 2.0;  // 200 ticks at 100 Hz
  MatchState s = make_match(cfg, 3);
  step(s, joins(3));
  // Only player 1 is ready; players 2 and 3 never answer.
  TickInputs ready1;
  ready1.players.push_back({1, {}, {{CommandKind::ready, {}}}});
  step(s, ready1);
  const std::int64_t first_ready_tick = s.tick - 1;
  REQUIRE(s.phase == Phase::lobby);
  REQUIRE(s.lobby_deadline_tick == first_ready_tick + 200);
  std::vector<Event> ev;
  while (s.phase == Phase::lobby && s.tick < first_ready_tick + 1000) {
    auto e = step(s, {}).events;
    ev.insert(ev.end(), e.begin(), e.end());
  }
  REQUIRE(s.phase == Phase::playing);
  CHECK(s.tick - 1 == first_ready_tick + 200);
  CHECK(of<LevelStarted>(ev).size() == 1);
  for (const Player& p : s.players) CHECK(p.ball != 0);  // the idle players play too
  CHECK(s.lobby_deadline_tick == -1);
}

TEST_CASE("Lobby: nobody ready, no countdown - everyone ready starts at once", "[match][lobby]") {
  MatchState s = make_match({}, 3);
  step(s, joins(2));
  run(s, 5000);
  CHECK(s.phase == Phase::lobby);
  CHECK(s.lobby_deadline_tick == -1);
  step(s, all_ready(s));
  CHECK(s.phase == Phase::playing);
}

TEST_CASE("Quit: the ball leaves at once, no life is lost, progress is kept", "[match][quit]") {
  MatchState s = started(2, 5);
  find_player(s, 1)->eco.coins = 321;
  const auto lives = find_player(s, 1)->eco.lives;
  const BallId ball = find_player(s, 1)->ball;
  REQUIRE(ball != 0);
  TickInputs q;
  q.quit.push_back(1);
  const auto ev = step(s, q).events;
  CHECK(of<PlayerFell>(ev).empty());
  const Player* p = find_player(s, 1);
  REQUIRE(p);
  CHECK(p->ball == 0);
  CHECK(find_ball(s.world, ball) == nullptr);
  CHECK(p->eco.lives == lives);
  CHECK(p->eco.coins == 321);
  CHECK(p->parked);
  // Ten seconds on: still no ball, still no life lost, the level is not restarted for it.
  const auto later = run(s, 1000);
  CHECK(find_player(s, 1)->ball == 0);
  CHECK(find_player(s, 1)->eco.lives == lives);

  SECTION("back: the ball returns with the same progress") {
    TickInputs back;
    back.back.push_back(1);
    step(s, back);
    step(s, {});
    CHECK(find_player(s, 1)->ball != 0);
    CHECK(find_player(s, 1)->eco.coins == 321);
    CHECK_FALSE(find_player(s, 1)->parked);
  }
}

TEST_CASE("Quit: the seat is given up for a new player", "[match][quit]") {
  MatchConfig cfg;
  cfg.max_players = 2;
  MatchState s = started(2, 5, cfg);
  TickInputs join3;
  join3.joins.push_back({3, "carol"});
  CHECK(of<JoinRefused>(step(s, join3).events).size() == 1);
  TickInputs q;
  q.quit.push_back(2);
  step(s, q);
  join3.joins[0].player = 4;
  CHECK(of<Joined>(step(s, join3).events).size() == 1);
  CHECK(find_player(s, 2) != nullptr);  // the quitter's progress is still there
}

TEST_CASE("Quit: when everyone quit, the level waits instead of restarting", "[match][quit]") {
  MatchState s = started(1, 9);
  TickInputs q;
  q.quit.push_back(1);
  step(s, q);
  const auto ev = run(s, 500);
  CHECK(of<LevelStarted>(ev).empty());
  CHECK(of<GameOver>(ev).empty());
  CHECK(s.phase == Phase::playing);
}

TEST_CASE("Names: a duplicate name gets a suffix", "[match][names]") {
  MatchState s = make_match({}, 1);
  TickInputs in;
  in.joins = {{1, "ann"}, {2, "ann"}, {3, "ann"}, {4, "sixteen-letters!"}, {5, "sixteen-letters!"}};
  step(s, in);
  REQUIRE(s.players.size() == 5);
  CHECK(find_player(s, 1)->name == "ann");
  CHECK(find_player(s, 2)->name == "ann-2");
  CHECK(find_player(s, 3)->name == "ann-3");
  CHECK(find_player(s, 4)->name == "sixteen-letters!");
  CHECK(find_player(s, 5)->name == "sixteen-letter-2");
  CHECK(find_player(s, 5)->name.size() <= 16);
}
