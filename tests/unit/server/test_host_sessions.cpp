// The host's side of sessions (issue 11), real protocol clients against GameHost in
// memory, time stepped by hand: commands that cannot be applied are answered and do not
// block the next; a client that dies holding a key stops pushing; a quit takes the ball.
#include <catch2/catch.hpp>

#include "app/game_host.hpp"
#include "fts/protocol/client.hpp"
#include "fts/protocol/codec.hpp"

using namespace fts;

namespace {

struct SessionsRig {
  server::Options options;
  sim::MatchConfig config;
  std::unique_ptr<server::GameHost> host;
  protocol::ClientEndpoint client;
  bool alive = true;  // false: the client process is gone (sends and hears nothing)
  std::uint64_t now = 1000;
  const std::string address = "10.0.0.1:5000";

  explicit SessionsRig(sim::MatchConfig cfg = {}) : config(cfg), client(named("ann")) {
    options.seed = 5;
    host = std::make_unique<server::GameHost>(options, config, protocol::ServerKey{});
    client.connect(now);
    for (int i = 0; i < 50 && client.state() != protocol::ClientState::connected; ++i) tick();
    REQUIRE(client.state() == protocol::ClientState::connected);
    tick();
  }
  static protocol::ClientConfig named(const std::string& name) {
    protocol::ClientConfig c;
    c.name = name;
    return c;
  }
  void tick() {
    if (alive) {
      client.update(now);
      for (auto& d : client.take_datagrams()) host->receive(address, d, now);
    }
    host->tick(now);
    for (auto& out : host->take_datagrams())
      if (alive) client.receive(out.bytes, now);
    now += 10;
  }
  void ticks(int n) {
    for (int i = 0; i < n; ++i) tick();
  }
  const sim::Player& me() { return *sim::find_player(host->match(), 1); }
  // Ready, then ticks until the level runs.
  void play() {
    client.send_command(protocol::CommandOp::ready, 0, now);
    for (int i = 0; i < 100 && host->match().phase != sim::Phase::playing; ++i) tick();
    REQUIRE(host->match().phase == sim::Phase::playing);
  }
  // Up held for 50 ms (one frame per tick), then the client process dies without a word.
  void hold_up_then_die() {
    for (int i = 0; i < 5; ++i) {
      client.send_input({0, 0, 1, false}, now);
      tick();
    }
    alive = false;
  }
};

}  // namespace

TEST_CASE("Host sessions: a command that cannot be applied is answered, and the next one too",
          "[server][host][sessions]") {
  SessionsRig rig;
  // A datagram with an unknown op, a buy of an unknown item and a buy without an item,
  // then a good command: hand-made on the client's own session.
  rig.client.send_input({0, 0, 0, false}, rig.now);
  auto real = rig.client.take_datagrams();
  REQUIRE(real.size() == 1);
  auto header = protocol::read_header(real[0]);
  REQUIRE(header);
  const std::vector<protocol::Message> messages = {protocol::Input{0, {}},
                                                   protocol::Command{1, protocol::CommandOp::unknown, 0, {}, {}},
                                                   protocol::Command{2, protocol::CommandOp::buy, 'z', {}, {}},
                                                   protocol::Command{3, protocol::CommandOp::buy, 0, {}, {}}};
  // Sealed with the client's keys in place of its own datagram (same header).
  protocol::SealedChannel channel(rig.client.session_keys(), protocol::SealDirection::client_to_server,
                                  protocol::SealDirection::server_to_client);
  rig.host->receive(rig.address, protocol::encode_sealed(channel, *header, messages), rig.now);
  rig.ticks(20);
  auto results = rig.client.take_results();
  REQUIRE(results.size() == 3);
  CHECK(results[0].code == "op");
  CHECK(results[1].code == "item");
  CHECK(results[2].code == "item");
  for (const auto& r : results) CHECK_FALSE(r.ok);
}

TEST_CASE("Host sessions: a client killed while holding a key loses no life", "[server][host][sessions]") {
  sim::MatchConfig cfg;
  SessionsRig rig(cfg);
  rig.play();
  const auto lives = rig.me().eco.lives;
  rig.hold_up_then_die();
  REQUIRE(sim::find_ball(rig.host->match().world, rig.me().ball));
  // Ten seconds of server time, up to the time-out: the ball stops, on the platform.
  rig.ticks(950);
  CHECK(rig.me().eco.lives == lives);
  CHECK(rig.me().ball != 0);
  const sim::Ball* after = sim::find_ball(rig.host->match().world, rig.me().ball);
  REQUIRE(after);
  CHECK(std::abs(after->vel.y) < 1.0);
}

TEST_CASE("Host sessions: with the expiry off (huge), the same crash drives the ball off", "[server][host][sessions]") {
  // The control for the test above: the expiry is what saves the life.
  sim::MatchConfig cfg;
  SessionsRig rig(cfg);
  rig.host.reset();
  rig.options.input_expiry_ms = 10000;
  rig.host = std::make_unique<server::GameHost>(rig.options, rig.config, protocol::ServerKey{});
  rig.client = protocol::ClientEndpoint(SessionsRig::named("ann"));
  rig.client.connect(rig.now);
  for (int i = 0; i < 50 && rig.client.state() != protocol::ClientState::connected; ++i) rig.tick();
  rig.tick();
  rig.play();
  const auto lives = rig.me().eco.lives;
  rig.hold_up_then_die();
  rig.ticks(950);
  CHECK(rig.me().eco.lives < lives);
}

TEST_CASE("Host sessions: a quit takes the ball off at once and keeps the coins", "[server][host][sessions]") {
  SessionsRig rig;
  rig.play();
  REQUIRE(rig.me().ball != 0);
  const auto lives = rig.me().eco.lives;
  rig.client.disconnect(rig.now, "quit");
  rig.ticks(3);
  CHECK(rig.me().ball == 0);
  CHECK(rig.me().parked);
  rig.ticks(500);
  CHECK(rig.me().eco.lives == lives);
}
