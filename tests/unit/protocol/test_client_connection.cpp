// ClientConnection: the token of the latest welcome, and resuming a lost connection with
// it from a fresh address, until the reconnect window has passed.
#include <catch2/catch.hpp>

#include "fts/protocol/connection.hpp"
#include "fts/protocol/server.hpp"
#include "harness.hpp"

using namespace fts::protocol;

namespace {

struct Rig {
  ServerEndpoint server;
  ClientConnection conn;
  bool link_up = true;
  std::uint64_t now = 100;

  explicit Rig(bool resume) : server(test::one_room(config(), server)), conn(client_config(), resume) { conn.connect(now); }

  static ServerConfig config() {
    ServerConfig c = test::test_server_config();
    c.timeout_ms = c.settings.timeout_ms = 1000;
    c.reconnect_window_ms = c.settings.reconnect_window_ms = 5000;
    return c;
  }
  static ClientConfig client_config() {
    ClientConfig c;
    c.name = "ann";
    c.connect_timeout_ms = 2000;
    return c;
  }
  // Each attempt sends from its own port, as a fresh socket would.
  std::string address() const { return "10.0.0.1:" + std::to_string(5000 + conn.attempt()); }

  void step() {
    now += 5;
    for (auto& d : conn.endpoint().take_datagrams())
      if (link_up) server.receive(address(), d, now);
    for (auto& out : server.take_datagrams())
      if (link_up && out.to == address()) conn.endpoint().receive(out.bytes, now);
    conn.update(now);
    server.update(now);
  }
  template <class Pred>
  bool run_until(Pred pred, std::uint64_t for_ms) { return test::step_until(*this, pred, for_ms); }
  bool connected() const { return test::welcomed(conn); }
};

}  // namespace

TEST_CASE("ClientConnection: a lost connection resumes with its token from a fresh address", "[protocol][connection]") {
  Rig rig(true);
  REQUIRE(rig.run_until([&] { return rig.connected(); }, 2000));
  const auto player = rig.conn.endpoint().welcome()->player_id;
  const std::string token = rig.conn.token();
  CHECK_FALSE(token.empty());
  CHECK(rig.conn.attempt() == 1);
  // A player (it pressed a key): its slot is held when the connection is lost.
  rig.conn.endpoint().send_input({1, 1, 0, false}, rig.now);
  rig.step();

  rig.link_up = false;  // the server hears nothing and says nothing
  REQUIRE(rig.run_until([&] { return rig.conn.attempt() == 2; }, 5000));
  CHECK(rig.conn.resuming());
  rig.link_up = true;
  REQUIRE(rig.run_until([&] { return rig.connected(); }, 3000));
  CHECK(rig.conn.endpoint().welcome()->reconnected);
  CHECK(rig.conn.endpoint().welcome()->player_id == player);
  CHECK_FALSE(rig.conn.resuming());

  SECTION("and gives up once the reconnect window has passed") {
    rig.link_up = false;
    REQUIRE(rig.run_until([&] { return rig.conn.gone(); }, 30000));
    const auto attempts = rig.conn.attempt();
    CHECK(attempts > 2);
    rig.run_until([] { return false; }, 5000);
    CHECK(rig.conn.attempt() == attempts);  // no attempts after giving up
  }
}

TEST_CASE("ClientConnection: without resuming, a lost connection stays lost - connect() resumes it",
          "[protocol][connection]") {
  Rig rig(false);
  REQUIRE(rig.run_until([&] { return rig.connected(); }, 2000));
  const auto player = rig.conn.endpoint().welcome()->player_id;
  rig.conn.endpoint().disconnect(rig.now, "script");
  REQUIRE(rig.run_until([&] { return rig.conn.state() == ClientState::disconnected; }, 1000));
  rig.run_until([] { return false; }, 3000);
  CHECK(rig.conn.attempt() == 1);
  rig.conn.connect(rig.now);  // a bot's "reconnect" step
  REQUIRE(rig.run_until([&] { return rig.connected(); }, 2000));
  CHECK(rig.conn.endpoint().welcome()->player_id == player);
}

TEST_CASE("ClientConnection: our own bye is never resumed, even when resuming is on", "[protocol][connection]") {
  Rig rig(true);
  REQUIRE(rig.run_until([&] { return rig.connected(); }, 2000));
  rig.conn.leave(rig.now, "quit");
  CHECK(rig.conn.state() == ClientState::disconnected);
  rig.run_until([] { return false; }, 15000);
  CHECK(rig.conn.attempt() == 1);
  CHECK_FALSE(rig.conn.resuming());
}
