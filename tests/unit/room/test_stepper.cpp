// The room stepper: every event numbered once, in order, the recent window capped at
// kRecentEvents, and a stepper taken up from (state, event_seq) going on as the first did.
#include <catch2/catch.hpp>

#include <vector>

#include "../match/match_test_util.hpp"
#include "fts/room/stepper.hpp"

using namespace fts;

namespace {

// Tick i's inputs: players 1..4 join, get ready, then each steers one way for a few
// seconds at a time, so that balls fall (player_fell, respawned) and enemies are hit.
sim::TickInputs inputs_at(int i) {
  if (i == 0) return test::joins(4);
  sim::TickInputs in;
  for (std::uint32_t p = 1; p <= 4; ++p) {
    sim::PlayerTick t;
    t.player = p;
    if (i == 1) t.commands.push_back({sim::CommandKind::ready, {}});
    t.input.move_x = static_cast<std::int8_t>((i / (240 + 70 * static_cast<int>(p))) % 2 == 0 ? 1 : -1);
    t.input.move_y = static_cast<std::int8_t>((i / (310 + 30 * static_cast<int>(p))) % 2 == 0 ? 1 : -1);
    in.players.push_back(t);
  }
  return in;
}

// Lives enough that nobody is out within the test: events keep coming.
sim::MatchConfig many_lives() {
  sim::MatchConfig c;
  c.player_lives = 50;
  return c;
}

}  // namespace

TEST_CASE("Room stepper: events numbered once, in order - the window keeps the newest", "[room][stepper]") {
  room::RoomStepper stepper(many_lives(), 5);
  std::vector<protocol::Event> all;
  for (int i = 0; i < 6000; ++i) {
    std::vector<protocol::Event> fresh;
    stepper.step(inputs_at(i), &fresh);
    all.insert(all.end(), fresh.begin(), fresh.end());
    REQUIRE(stepper.recent().size() <= room::kRecentEvents);
  }
  INFO(all.size() << " events");
  REQUIRE(all.size() > room::kRecentEvents);  // the window has been full
  for (std::size_t k = 0; k < all.size(); ++k) CHECK(all[k].seq == k + 1);
  CHECK(stepper.event_seq() == all.size());
  // The window is the newest kRecentEvents, oldest first, and the snapshot carries it.
  REQUIRE(stepper.recent().size() == room::kRecentEvents);
  CHECK(stepper.recent().front().seq == all.size() - room::kRecentEvents + 1);
  CHECK(stepper.recent().back().seq == all.size());
  CHECK(stepper.snapshot().events.size() == room::kRecentEvents);
}

TEST_CASE("Room stepper: taken up from its state and event seq, it goes on bit for bit", "[room][stepper]") {
  room::RoomStepper first(sim::MatchConfig{}, 9);
  for (int i = 0; i < 1500; ++i) first.step(inputs_at(i));
  room::RoomStepper resumed(first.match(), first.event_seq());
  CHECK(resumed.recent().empty());  // the window starts empty at a resume
  for (int i = 1500; i < 3000; ++i) {
    std::vector<protocol::Event> a, b;
    first.step(inputs_at(i), &a);
    resumed.step(inputs_at(i), &b);
    REQUIRE(a.size() == b.size());
    for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k].seq == b[k].seq);
  }
  CHECK(sim::match_hash(first.match()) == sim::match_hash(resumed.match()));
  CHECK(first.event_seq() == resumed.event_seq());
}
