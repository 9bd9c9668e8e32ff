// The fleet's view of GameHost (observe) and a drain end to end in memory: real protocol
// clients against GameHost, time stepped by hand, no Agones and no /metrics.
#include <catch2/catch.hpp>

#include "app/game_host.hpp"
#include "../../support/host_rig.hpp"
#include "fleet/fleet.hpp"
#include "fleet/fleet_state.hpp"
#include "fts/protocol/client.hpp"

using namespace fts;

namespace {

struct Rig : test::HostRig {
  Rig() { start(); }
  // One tick, then the fleet's per-tick work.
  void tick(server::Fleet& fleet) {
    send();
    host->tick(now);
    deliver();
    fleet.tick(*host, 0, 0, now);
    now += 10;
  }
};

}  // namespace

TEST_CASE("Fleet: observe() counts the connected players, the seats and the live room's code", "[fleet]") {
  Rig rig;
  server::Fleet fleet(rig.options);
  CHECK(server::observe(*rig.host) == server::FleetState{});
  auto& a = rig.add("ann");
  rig.add("bob");
  for (int i = 0; i < 20; ++i) rig.tick(fleet);
  const auto s = server::observe(*rig.host);
  const auto ids = rig.host->room_ids();
  REQUIRE(ids.size() == 1);
  CHECK(s.rooms == 1);
  CHECK(s.seats == 2);
  CHECK(s.room_codes == std::vector<std::string>{rig.host->room(ids[0])->code()});
  CHECK(s.players == std::set<std::string>{"ann", "bob"});
  CHECK(s.phase == "lobby");
  CHECK_FALSE(s.draining);
  a.disconnect(rig.now);
  for (int i = 0; i < 5; ++i) rig.tick(fleet);
  CHECK(server::observe(*rig.host).players == std::set<std::string>{"bob"});
  CHECK(server::observe(*rig.host).seats == 1);  // a quit gives the seat back
}

TEST_CASE("Fleet: a drain refuses new players and is over when the last one leaves", "[fleet]") {
  Rig rig;
  rig.options.drain_grace_ms = 60000;
  server::Fleet fleet(rig.options);
  auto& a = rig.add("ann");
  for (int i = 0; i < 20; ++i) rig.tick(fleet);
  REQUIRE(a.state() == protocol::ClientState::connected);

  fleet.drain(*rig.host, rig.now);
  CHECK(rig.host->draining());
  CHECK(server::observe(*rig.host).phase == "draining");
  auto& late = rig.add("late");
  for (int i = 0; i < 20; ++i) rig.tick(fleet);
  REQUIRE(late.error());
  CHECK(late.error()->code == "draining");
  CHECK(server::observe(*rig.host).players == std::set<std::string>{"ann"});
  CHECK_FALSE(fleet.finished(rig.now));  // ann still plays

  a.disconnect(rig.now);
  for (int i = 0; i < 5; ++i) rig.tick(fleet);
  CHECK(fleet.finished(rig.now));  // no Agones: over as soon as the last room ended
}

TEST_CASE("Fleet: a drain is over when the grace runs out, players or not", "[fleet]") {
  Rig rig;
  rig.options.drain_grace_ms = 500;
  server::Fleet fleet(rig.options);
  rig.add("ann");
  for (int i = 0; i < 20; ++i) rig.tick(fleet);
  const auto start = rig.now;
  fleet.drain(*rig.host, start);
  while (rig.now < start + 490) {
    rig.tick(fleet);
    REQUIRE_FALSE(fleet.finished(rig.now - 10));
  }
  for (int i = 0; i < 3; ++i) rig.tick(fleet);
  CHECK(fleet.finished(rig.now));
}
