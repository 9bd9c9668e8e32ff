#include <catch2/catch.hpp>

#include "seed_situation.hpp"
#include "ui/hud.hpp"
#include "ui/render.hpp"

using namespace fts::client;
using fts::protocol::Phase;

TEST_CASE("HUD line in the original's words", "[client][hud]") {
  auto snap = fts::client::test::seed_snapshot(Phase::play);
  ViewState view;
  view.my_player_id = 1;
  SECTION("without connection figures") { CHECK(hud_line(snap, view) == "Level: 3   Coins: 286   Lives: 1"); }
  SECTION("with ping and loss") {
    view.ping_ms = 23.4;
    view.loss_percent = 1.25;
    CHECK(hud_line(snap, view) == "Level: 3   Coins: 286   Lives: 1   Ping: 23 ms   Loss: 1.2%");
  }
  SECTION("large coin counts get thousands separators") {
    snap.players[0].coins = 1'234'567;
    CHECK(hud_line(snap, view) == "Level: 3   Coins: 1,234,567   Lives: 1");
  }
  SECTION("a spectator without a player sees the level") {
    view.my_player_id = 9;
    CHECK(hud_line(snap, view) == "Level: 3");
  }
  SECTION("issue 26: spawn protection shows its seconds left, rounded up, while it lasts") {
    view.tick_rate_hz = 100;
    snap.tick = 1000;
    snap.players[0].protected_until_tick = 1250;
    CHECK(hud_line(snap, view) == "Level: 3   Coins: 286   Lives: 1   Protected: 3s");
    snap.tick = 1249;
    CHECK(hud_line(snap, view) == "Level: 3   Coins: 286   Lives: 1   Protected: 1s");
    snap.tick = 1250;  // ended
    CHECK(hud_line(snap, view) == "Level: 3   Coins: 286   Lives: 1");
    snap.players[0].protected_until_tick = 0;  // none
    CHECK(hud_line(snap, view) == "Level: 3   Coins: 286   Lives: 1");
  }
}

TEST_CASE("players line lists every player with coins and lives", "[client][hud]") {
  auto snap = fts::client::test::seed_snapshot(Phase::play);
  auto bob = fts::client::test::seed_player();
  bob.id = 2;
  bob.name = "bob";
  bob.coins = 1;
  bob.lives = 3;
  snap.players.push_back(bob);
  ViewState view;
  view.my_player_id = 1;
  CHECK(players_line(snap, view) == "Players: ann (you) 286 coins 1 life | bob 1 coin 3 lives");
}

TEST_CASE("the rendered screen carries the HUD, the players and the help line", "[client][hud]") {
  auto snap = fts::client::test::seed_snapshot(Phase::play);
  ViewState view;
  view.my_player_id = 1;
  view.ping_ms = 12;
  const Screen s = render(snap, snap, 0, {100, 30}, view);
  CHECK(s.line(0).rfind("Level: 3   Coins: 286   Lives: 1   Ping: 12 ms", 0) == 0);
  bool legend = false;
  for (const auto& l : s.lines()) legend = legend || l.find("@ ann") != std::string::npos;
  CHECK(legend);
  CHECK(s.line(29).rfind("Move: arrows/WASD/hjkl/mouse   Fire rockets: space   Chat: t   Quit: q", 0) == 0);
  SECTION("a status line such as connection trouble is shown") {
    view.status = "connection lost, reconnecting...";
    CHECK(render(snap, snap, 0, {100, 30}, view).line(0).find("connection lost, reconnecting...") != std::string::npos);
  }
}

TEST_CASE("events are described for the message line", "[client][hud]") {
  auto snap = fts::client::test::seed_snapshot(Phase::play);
  using fts::protocol::Event;
  using fts::protocol::EventKind;
  CHECK(describe_event(Event{1, 1, EventKind::purchase, 1, 'm', 35}, snap, 1) == "You bought mass for 35 coins.");
  CHECK(describe_event(Event{1, 1, EventKind::enemy_fell, 7, 1, 41}, snap, 2) ==
        "ann knocked an enemy off: +41 coins.");
  CHECK(describe_event(Event{1, 1, EventKind::level_complete, 0, 0, 3}, snap, 1) == "Level 3 Complete");
}

TEST_CASE("lobby and shop countdowns from the snapshot's deadline", "[client][hud][countdown]") {
  Snapshot s;
  s.tick = 700;
  CHECK(countdown_s(s, 100) == -1);  // no deadline: no countdown
  s.deadline_tick = 3000;
  CHECK(countdown_s(s, 100) == 23);
  CHECK(countdown_s(s, 50) == 46);
  s.deadline_tick = 701;
  CHECK(countdown_s(s, 100) == 1);  // rounded up: never "0 s" while waiting
  s.deadline_tick = 700;
  CHECK(countdown_s(s, 100) == 0);
  // The lobby screen shows it.
  s.phase = Phase::lobby;
  s.deadline_tick = 3000;
  PlayerState p;
  p.id = 1;
  p.name = "ann";
  s.players.push_back(p);
  ViewState view;
  view.my_player_id = 1;
  const Screen screen = render(s, s, 0, {100, 30}, view);
  bool found = false;
  for (int r = 0; r < screen.rows(); ++r)
    found = found || screen.line(r).find("The match starts in 23 s") != std::string::npos;
  CHECK(found);
}
