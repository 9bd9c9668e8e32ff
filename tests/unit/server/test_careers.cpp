// A room's careers (issue 41, app/careers.hpp), stepped by hand: a player with an
// identity is followed from its match's start; knocks, falls, the level and coins are
// counted; its result comes once when it runs out of lives; a guest is not followed; a
// quit after the match ran gives "quit", a closing room "closed"; the journal's form
// brings a match back under the same key.
#include <catch2/catch.hpp>

#include "app/careers.hpp"

using namespace fts;
using fts::server::Careers;

namespace {

sim::MatchState running_match() {
  sim::MatchState m = sim::make_match(sim::MatchConfig{}, 7);
  m.phase = sim::Phase::playing;
  m.level = 1;
  m.matches_started = 1;
  for (std::uint32_t id : {1u, 2u}) {
    sim::Player p;
    p.id = id;
    p.name = id == 1 ? "ann" : "guest";
    p.eco.lives = 2;
    p.eco.coins = 10;
    m.players.push_back(p);
  }
  return m;
}

const std::string kAnn = "aaaa0000000000000000000000000001";

}  // namespace

TEST_CASE("Careers: counted from the match's start, one result when the lives run out", "[server][profiles]") {
  Careers c;
  c.new_key = [] { return std::string(32, 'k'); };
  c.identify(1, kAnn, "ann");
  c.identify(2, "", "guest");
  sim::MatchState m = running_match();
  CHECK(c.step(m, {}, 100).empty());
  REQUIRE(c.tally(1));
  CHECK_FALSE(c.tally(2));  // a guest
  std::vector<sim::Event> ev = {sim::EnemyDefeated{5, 1, 1, 3}, sim::EnemyDefeated{6, 2, 1, 3},
                                sim::PlayerFell{1, 9, 1, 1}};
  m.level = 3;
  m.players[0].eco.coins = 40;
  std::vector<std::uint32_t> changed;
  CHECK(c.step(m, ev, 101, &changed).empty());
  CHECK_FALSE(changed.empty());
  m.players[0].eco.coins = 5;  // spent: the most held stays
  m.players[0].eco.lives = 0;
  const auto results = c.step(m, {sim::PlayerFell{1, 9, 3, 0}}, 160);
  REQUIRE(results.size() == 1);
  const auto& r = results[0];
  CHECK(r.fingerprint == kAnn);
  CHECK(r.key == std::string(32, 'k'));
  CHECK(r.name == "ann");
  CHECK(r.level == 3);
  CHECK(r.coins == 40);
  CHECK(r.knocks == 1);
  CHECK(r.lives_lost == 2);
  CHECK(r.ending == profiles::Ending::game_over);
  CHECK(r.ended_unix_s == 160);
  // Once: the next steps, the release and the room's close add nothing.
  CHECK(c.step(m, {}, 170).empty());
  CHECK(c.close(100, 180).empty());
  CHECK_FALSE(c.released(1, 100, 190));
}

TEST_CASE("Careers: a quit ends with the release, a closing room closes - the journal's form resumes",
          "[server][profiles]") {
  Careers c;
  int n = 0;
  c.new_key = [&] { return std::string(31, 'a') + static_cast<char>('0' + n++); };
  c.identify(1, kAnn, "ann");
  sim::MatchState m = running_match();
  c.step(m, {sim::EnemyDefeated{5, 1, 1, 3}}, 100);
  c.step(m, {sim::EnemyDefeated{5, 1, 1, 3}}, 100);
  const std::string saved = c.saved(1);
  CHECK_FALSE(saved.empty());

  // A resumed room: the same match, the same key, the counts so far.
  Careers back;
  back.restore(1, kAnn, saved);
  REQUIRE(back.tally(1));
  CHECK(*back.tally(1) == *c.tally(1));
  const auto closed = back.close(100, 500);
  REQUIRE(closed.size() == 1);
  CHECK(closed[0].ending == profiles::Ending::closed);
  CHECK(closed[0].key == c.tally(1)->key);
  CHECK(closed[0].knocks == 1);  // the tally starts at the first step: the first knock came with it

  const auto quit = c.released(1, 100, 600);
  REQUIRE(quit);
  CHECK(quit->ending == profiles::Ending::quit);
  CHECK_FALSE(c.tally(1));
  back.restore(2, kAnn, "{not json");
  CHECK_FALSE(back.tally(2));
}
