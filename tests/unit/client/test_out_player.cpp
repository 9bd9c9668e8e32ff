// An out player (no lives left) is told what it can do and when it plays again (issue 26:
// with 0 coins the footer offered "Buy: m s a r l x b" and `m` said "the shop is closed"
// while it was open for the others).
#include <catch2/catch.hpp>

#include "fts/room/snapshot_build.hpp"
#include "fts/sim/match.hpp"
#include "fts/sim/match_view.hpp"
#include "seed_situation.hpp"
#include "ui/hud.hpp"
#include "ui/panel.hpp"
#include "ui/render.hpp"

using namespace fts;
using namespace fts::client;
using fts::protocol::Phase;

TEST_CASE("An out player's footer says when it plays again, in the shop and while watching", "[client][watch]") {
  auto s = fts::client::test::seed_snapshot(Phase::shop);
  s.players[0].lives = 0;
  s.players[0].alive = false;
  s.players[0].coins = 0;
  auto other = fts::client::test::seed_player();
  other.id = 2;
  other.name = "bob";
  s.players.push_back(other);
  ViewState view;
  view.my_player_id = 1;
  const std::string shop = footer_text(s, view, 120);
  CHECK(shop.find("Buy:") == std::string::npos);
  CHECK(shop.find("you play again when this match ends") != std::string::npos);
  s.phase = Phase::play;
  const std::string play = footer_text(s, view, 200);
  CHECK(play.rfind("Watching bob", 0) == 0);
  CHECK(play.find("you play again when this match ends") != std::string::npos);
  // Still in the match: the shop's keys as before.
  s.players[0].lives = 1;
  s.players[0].alive = true;
  s.phase = Phase::shop;
  CHECK(footer_text(s, view, 120).rfind("Buy: m s a r l x b", 0) == 0);
}

TEST_CASE("A buy refused for the phase tells an out player why, not 'the shop is closed'", "[client][hud]") {
  auto me = fts::client::test::seed_player();
  me.lives = 0;
  CHECK(refusal_text("phase", "", 'm', &me) == "you are out of lives: you play again when this match ends");
  me.lives = 2;
  CHECK(refusal_text("phase", "", 'm', &me) == "not now: the shop is closed");
}

TEST_CASE("An away player is marked in the legend, not shown as playing", "[client][watch]") {
  // Issue 26: away players looked live in the legend.
  auto s = fts::client::test::seed_snapshot(Phase::play);
  auto bob = fts::client::test::seed_player();
  bob.id = 2;
  bob.name = "bob";
  bob.away = true;
  s.players.push_back(bob);
  ViewState view;
  view.my_player_id = 1;
  std::string text;
  for (const auto& l : render(s, s, 0, {120, 40}, view).lines()) text += l + "\n";
  CHECK(text.find("bob") != std::string::npos);
  CHECK(text.find("L away") != std::string::npos);
  s.players[1].away = false;
  text.clear();
  for (const auto& l : render(s, s, 0, {120, 40}, view).lines()) text += l + "\n";
  CHECK(text.find("away") == std::string::npos);
}

TEST_CASE("The snapshot says who is away: a lost or quit player's client", "[client][watch]") {
  sim::MatchConfig cfg;
  auto m = sim::make_match(cfg, 1);
  sim::TickInputs in;
  in.joins = {{1, "ann"}, {2, "bob"}};
  sim::step(m, in);
  sim::TickInputs gone;
  gone.away = {2};
  sim::step(m, gone);
  const auto snap = fts::room::build_snapshot(sim::make_view(m), {});
  REQUIRE(snap.players.size() == 2);
  CHECK_FALSE(snap.players[0].away);
  CHECK(snap.players[1].away);
}
