// Players' names as the host shows them (issue 26): the console and chat give the name
// the match gave (two "ann" are "ann" and "ann-2" on every screen), and a newcomer is not
// handed the events of players who left before it came (it can never learn their names:
// its log said "player 6 left.").
#include <catch2/catch.hpp>

#include <set>

#include "app/game_host.hpp"
#include "../../support/host_rig.hpp"
#include "fts/protocol/client.hpp"

using namespace fts;
using protocol::ClientState;
using protocol::EventKind;

namespace {

struct NamesRig : test::HostRig {
  NamesRig() {
    options.seed = 5;
    options.reconnect_window_ms = 200;  // a quit player's slot is released soon
    start();
  }
  protocol::ClientEndpoint& join(const std::string& name) {
    auto& c = add(name);
    for (int i = 0; i < 50 && c.state() == ClientState::connecting; ++i) tick();
    ticks(10);  // the match takes the player in at its next tick; a snapshot follows
    return c;
  }
  void ticks(int n) {
    for (int i = 0; i < n; ++i) tick();
  }
};

}  // namespace

TEST_CASE("Names: the console's players and chat lines name a player as its screen does", "[server][names]") {
  NamesRig rig;
  auto& first = rig.join("ann");
  auto& second = rig.join("ann");
  REQUIRE(first.state() == ClientState::connected);
  REQUIRE(second.state() == ClientState::connected);
  const auto* snap = second.latest_snapshot();
  REQUIRE(snap);
  std::set<std::string> on_screen;
  for (const auto& p : snap->players) on_screen.insert(p.name);
  REQUIRE(on_screen == std::set<std::string>{"ann", "ann-2"});

  auto players = rig.console(R"({"cmd":"players"})");
  REQUIRE(players["players"].size() == 2);
  for (const auto& p : players["players"]) {
    const auto id = p["player"].get<std::uint32_t>();
    CHECK(p["name"] == (id == first.welcome()->player_id ? "ann" : "ann-2"));
  }

  second.send_chat("hello", rig.now);
  rig.ticks(10);
  const auto got = first.take_chats();
  REQUIRE(got.size() == 1);
  CHECK(got[0].name == "ann-2");
}
