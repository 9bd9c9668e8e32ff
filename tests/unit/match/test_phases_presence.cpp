// Phases with connection presence: an away player does not hold up the lobby or shop.
#include <catch2/catch.hpp>

#include "fts/sim/match.hpp"

using namespace fts::sim;

TEST_CASE("Phases: the lobby starts when every connected player is ready", "[match][phases]") {
  MatchState s = make_match(MatchConfig{}, 3);
  TickInputs join;
  join.joins = {{1, "ann"}, {2, "bob"}};
  step(s, join);
  TickInputs ready1;
  ready1.players = {{1, {}, {{CommandKind::ready, {}}}}};
  step(s, ready1);
  step(s, {});
  CHECK(s.phase == Phase::lobby);  // bob is connected and not ready
  TickInputs away;
  away.away = {2};
  step(s, away);
  step(s, {});
  CHECK(s.phase == Phase::playing);  // bob went away: ann alone decides
  REQUIRE(find_player(s, 2) != nullptr);  // but bob keeps his place
  CHECK_FALSE(find_player(s, 2)->connected);
  TickInputs back;
  back.back = {2};
  step(s, back);
  CHECK(find_player(s, 2)->connected);
}
