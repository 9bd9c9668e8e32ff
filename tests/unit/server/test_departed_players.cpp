// Issue 37, point 3: "out of lives" is coherent. A player out of lives who watches is
// never dropped for idling, and a player who leaves a running match and comes back with
// its token is the same player (same lives, same coins) however long it was away, until
// the match ends: leaving and rejoining was a way to get three fresh lives and the
// median coins. Real protocol clients against GameHost in memory, time stepped by hand.
#include <catch2/catch.hpp>

#include "../../support/host_rig.hpp"

using namespace fts;

namespace {

constexpr protocol::InputFrame kLeft{0, -1, 0, false};
constexpr protocol::InputFrame kFire{0, 0, 0, true};  // real input that moves nothing (no rockets)

struct DepartedRig : test::HostRig {
  explicit DepartedRig(std::uint32_t idle_ms, std::uint32_t window_ms) {
    options.seed = 5;
    options.idle_timeout_ms = idle_ms;
    options.reconnect_window_ms = window_ms;
    start();
  }
  std::uint32_t id(std::size_t i) const { return clients[i]->welcome()->player_id; }
  const sim::Player* player(std::size_t i) const { return sim::find_player(host->match(), sim::PlayerId{id(i)}); }
  // Every client ready, then ticks until the level runs.
  void play() {
    for (auto& c : clients) c->send_command(protocol::CommandOp::ready, 0, now);
    for (int i = 0; i < 100 && host->match().phase != sim::Phase::playing; ++i) tick();
    REQUIRE(host->match().phase == sim::Phase::playing);
  }
  // Client `i` thrusts left until its ball falls off the platform once; the others press
  // `others` (none: idle).
  void fall_once(std::size_t i, const std::optional<protocol::InputFrame>& others = {}) {
    const std::int64_t lives = player(i)->eco.lives;
    for (int t = 0; t < 1000 && player(i)->eco.lives == lives; ++t) {
      clients[i]->send_input(kLeft, now);
      if (others)
        for (std::size_t j = 0; j < clients.size(); ++j)
          if (j != i && clients[j]->state() == protocol::ClientState::connected) clients[j]->send_input(*others, now);
      tick();
    }
    REQUIRE(player(i)->eco.lives == lives - 1);
  }
  void run_ms(std::uint64_t ms, std::size_t active) {
    for (const std::uint64_t end = now + ms; now < end;) {
      clients[active]->send_input(kFire, now);
      tick();
    }
  }
};

}  // namespace

TEST_CASE("Out of lives: a watcher is never dropped for idling - an idle player still is", "[server][idle]") {
  DepartedRig rig(/*idle_ms=*/2000, /*window_ms=*/60000);
  rig.config.player_lives = 1;
  rig.start();
  rig.add("ann");   // falls off once: out of lives, watches
  rig.add("bob");   // plays on (presses fire)
  rig.add("cy");    // alive and idle: dropped
  REQUIRE(rig.connect_all());
  rig.tick();
  rig.play();
  rig.fall_once(0, kFire);
  REQUIRE_FALSE(rig.player(0)->in_match());
  REQUIRE(rig.host->match().phase == sim::Phase::playing);
  rig.run_ms(5000, 1);  // 2.5 idle time-outs of playing: ann and cy send heartbeats only
  CHECK(rig.host->match().phase == sim::Phase::playing);
  CHECK(rig.clients[0]->state() == protocol::ClientState::connected);
  CHECK_FALSE(rig.clients[0]->error().has_value());
  REQUIRE(rig.clients[2]->error().has_value());
  CHECK(rig.clients[2]->error()->code == "idle");
}

TEST_CASE("Out of lives: a player who quits a running match and comes back after the window is the same player",
          "[server][departed]") {
  DepartedRig rig(/*idle_ms=*/0, /*window_ms=*/1000);
  rig.add("ann");
  rig.add("bob");
  REQUIRE(rig.connect_all());
  rig.tick();
  rig.play();
  rig.fall_once(0, kFire);  // ann: 2 lives left
  const std::uint32_t ann = rig.id(0);
  const std::string token = rig.clients[0]->welcome()->token;
  const sim::Economy before = rig.player(0)->eco;
  REQUIRE(before.lives == 2);

  rig.clients[0]->disconnect(rig.now);
  rig.run_ms(5000, 1);  // five reconnect windows
  REQUIRE(rig.host->match().phase == sim::Phase::playing);
  const sim::Player* kept = sim::find_player(rig.host->match(), sim::PlayerId{ann});
  REQUIRE(kept != nullptr);  // still in the match, parked
  CHECK(kept->parked);

  protocol::ClientConfig back;
  back.name = "ann";
  back.token = token;
  auto& again = rig.connect(back);
  for (int i = 0; i < 50 && again.state() != protocol::ClientState::connected; ++i) {
    rig.clients[1]->send_input(kFire, rig.now);
    rig.tick();
  }
  REQUIRE(again.state() == protocol::ClientState::connected);
  CHECK(again.welcome()->reconnected);
  CHECK(again.welcome()->player_id == ann);
  rig.tick();
  const sim::Player* p = sim::find_player(rig.host->match(), sim::PlayerId{ann});
  REQUIRE(p != nullptr);
  CHECK(p->eco.lives == 2);  // not 3 fresh lives
  CHECK(p->eco.coins == before.coins);  // not the late joiner's median
  CHECK(rig.host->match().players.size() == 2);
}

TEST_CASE("Out of lives: a connection lost for longer than the window keeps the player for the match",
          "[server][departed]") {
  DepartedRig rig(/*idle_ms=*/0, /*window_ms=*/1000);
  rig.options.timeout_ms = 500;
  rig.start();
  rig.add("ann");
  rig.add("bob");
  REQUIRE(rig.connect_all());
  rig.tick();
  rig.play();
  const std::uint32_t ann = rig.id(0);
  const std::string token = rig.clients[0]->welcome()->token;
  // ann's process dies: nothing from it any more (its endpoint is replaced by a silent one).
  rig.clients[0] = std::make_unique<protocol::ClientEndpoint>(protocol::ClientConfig{});
  rig.run_ms(4000, 1);
  const sim::Player* kept = sim::find_player(rig.host->match(), sim::PlayerId{ann});
  REQUIRE(kept != nullptr);
  CHECK(kept->parked);      // its ball left the platform at the window's end
  CHECK(kept->eco.lives == 3);

  protocol::ClientConfig back;
  back.name = "ann";
  back.token = token;
  auto& again = rig.connect(back);
  for (int i = 0; i < 50 && again.state() != protocol::ClientState::connected; ++i) rig.tick();
  REQUIRE(again.state() == protocol::ClientState::connected);
  CHECK(again.welcome()->player_id == ann);
}

TEST_CASE("Out of lives: outside a running match (the lobby) the reconnect window still frees the player",
          "[server][departed]") {
  DepartedRig rig(/*idle_ms=*/0, /*window_ms=*/1000);
  rig.add("ann");
  rig.add("bob");
  REQUIRE(rig.connect_all());
  rig.tick();
  const std::uint32_t ann = rig.id(0);
  rig.clients[0]->disconnect(rig.now);
  for (int i = 0; i < 300; ++i) rig.tick();
  CHECK(rig.host->match().phase == sim::Phase::lobby);
  CHECK(sim::find_player(rig.host->match(), sim::PlayerId{ann}) == nullptr);
}

TEST_CASE("Out of lives: once nobody plays the match on, the window frees the departed players",
          "[server][departed]") {
  // Else a watcher would wait for ever on a level that everyone with lives has left.
  DepartedRig rig(/*idle_ms=*/0, /*window_ms=*/1000);
  rig.config.player_lives = 1;
  rig.start();
  rig.add("ann");
  rig.add("bob");
  rig.add("cy");  // out of lives: watches
  REQUIRE(rig.connect_all());
  rig.tick();
  rig.play();
  rig.fall_once(2, kFire);
  REQUIRE_FALSE(rig.player(2)->in_match());
  const std::uint32_t ann = rig.id(0), bob = rig.id(1);
  rig.clients[0]->disconnect(rig.now);
  rig.clients[1]->disconnect(rig.now);
  for (int i = 0; i < 300; ++i) rig.tick();  // three windows
  CHECK(sim::find_player(rig.host->match(), sim::PlayerId{ann}) == nullptr);
  CHECK(sim::find_player(rig.host->match(), sim::PlayerId{bob}) == nullptr);
  CHECK(rig.host->match().phase == sim::Phase::game_over);  // the watcher's match ended
}
