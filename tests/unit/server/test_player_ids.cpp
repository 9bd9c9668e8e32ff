// Player ids are never reused in a server's life (issue 36 point 10): a new session took
// the lowest free id, so a newcomer inherited a departed player's id, and with it the
// enemies' credit for that player's touches. Real protocol clients, time stepped by hand.
#include <catch2/catch.hpp>

#include "../../support/host_rig.hpp"

using namespace fts;

namespace {

std::uint32_t id_of(const protocol::ClientEndpoint& c) { return c.welcome() ? c.welcome()->player_id : 0; }

// A new client, ticked until it is welcomed (at most 50 ticks); its player id or 0.
std::uint32_t join(test::HostRig& rig, const std::string& name) {
  auto& c = rig.add(name);
  for (int i = 0; i < 50 && c.state() == protocol::ClientState::connecting; ++i) rig.tick();
  return id_of(c);
}

void kick(test::HostRig& rig, std::uint32_t id) {
  REQUIRE(rig.console(R"({"cmd":"kick","player":)" + std::to_string(id) + "}")["ok"] == true);
  rig.tick();
}

}  // namespace

TEST_CASE("Player ids: a newcomer never gets the id of a player who left", "[server][ids]") {
  test::HostRig rig;
  rig.options.max_players = 4;
  rig.start();
  const std::uint32_t ann = join(rig, "ann"), bob = join(rig, "bob");
  REQUIRE(ann == 1);
  REQUIRE(bob == 2);
  // ann is gone (her session released): the next player is not given her 1.
  kick(rig, ann);
  const std::uint32_t cy = join(rig, "cy");
  CHECK(cy == 3);
  // Everybody gone: still no id given twice.
  kick(rig, bob);
  kick(rig, cy);
  REQUIRE(rig.host->endpoint().sessions().empty());
  CHECK(join(rig, "dan") == 4);
  CHECK(join(rig, "eve") == 5);
}

TEST_CASE("Player ids: a match never names a player who left", "[server][ids]") {
  test::HostRig rig;
  rig.start();
  auto& ann = rig.add("ann");
  REQUIRE(rig.connect_all());
  ann.send_command(protocol::CommandOp::ready, 0, rig.now);
  for (int i = 0; i < 300 && rig.host->match().phase != sim::Phase::playing; ++i) rig.tick();
  REQUIRE(rig.host->match().phase == sim::Phase::playing);
  const std::uint32_t ann_id = id_of(ann);
  kick(rig, ann_id);
  const std::uint32_t bob = join(rig, "bob");
  for (int i = 0; i < 5; ++i) rig.tick();
  CHECK(bob != ann_id);
  const auto& m = rig.host->match();
  CHECK(sim::find_player(m, ann_id) == nullptr);
  for (const auto& [ball, b] : m.bodies) {
    CHECK(b.owner != sim::PlayerId{ann_id});
    CHECK(b.credit != sim::PlayerId{ann_id});
  }
}

// A server of a fleet (a fleet secret) starts its ids at a point of [2^20, 2^31) drawn from
// its key; alone, at 1 (issue 42: a room handed to a peer keeps its ids).
TEST_CASE("Player ids: a fleet server's first id comes from its key", "[server][ids]") {
  test::HostRig rig;
  rig.options.fleet_secret_path = "fleet.secret";  // only its presence counts here
  rig.start();
  const std::uint32_t ann = join(rig, "ann");
  CHECK(ann >= (1u << 20));
  CHECK(ann < (1u << 31));
  CHECK(join(rig, "bob") == ann + 1);
  test::HostRig other;  // another key
  other.key[0] ^= 0x5a;
  other.options.fleet_secret_path = "fleet.secret";
  other.start();
  CHECK(join(other, "cy") != ann);
}
