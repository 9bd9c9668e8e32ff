// The fleet's view of GameHost (observe) and a drain end to end in memory: real protocol
// clients against GameHost, time stepped by hand, no Agones and no /metrics.
#include <catch2/catch.hpp>

#include "app/game_host.hpp"
#include "fleet/fleet.hpp"
#include "fleet/fleet_state.hpp"
#include "fts/protocol/client.hpp"

using namespace fts;

namespace {

struct Rig {
  server::Options options;
  sim::MatchConfig config;
  std::unique_ptr<server::GameHost> host;
  std::vector<std::unique_ptr<protocol::ClientEndpoint>> clients;
  std::uint64_t now = 1000;

  Rig() { host = std::make_unique<server::GameHost>(options, config, protocol::ServerKey{}); }
  protocol::ClientEndpoint& add(const std::string& name) {
    protocol::ClientConfig c;
    c.name = name;
    clients.push_back(std::make_unique<protocol::ClientEndpoint>(c));
    clients.back()->connect(now);
    return *clients.back();
  }
  void tick(server::Fleet& fleet) {
    for (std::size_t i = 0; i < clients.size(); ++i) {
      clients[i]->update(now);
      for (auto& d : clients[i]->take_datagrams()) host->receive("10.0.0." + std::to_string(i + 1) + ":5000", d, now);
    }
    host->tick(now);
    for (auto& out : host->take_datagrams()) {
      const auto idx = std::stoul(out.to.substr(7, out.to.find(':') - 7)) - 1;
      clients[idx]->receive(out.bytes, now);
    }
    fleet.tick(*host, 0, 0, now);
    now += 10;
  }
};

}  // namespace

TEST_CASE("Fleet: observe() counts the connected players and the live room", "[fleet]") {
  Rig rig;
  server::Fleet fleet(rig.options);
  CHECK(server::observe(*rig.host) == server::FleetState{0, {}, "lobby", false});
  auto& a = rig.add("ann");
  rig.add("bob");
  for (int i = 0; i < 20; ++i) rig.tick(fleet);
  CHECK(server::observe(*rig.host) == server::FleetState{1, {"ann", "bob"}, "lobby", false});
  a.disconnect(rig.now);
  for (int i = 0; i < 5; ++i) rig.tick(fleet);
  CHECK(server::observe(*rig.host).players == std::set<std::string>{"bob"});
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
