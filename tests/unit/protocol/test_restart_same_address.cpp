// A client process that restarts on the same address with its token gets a fresh
// session (regression: the server used to resend the old welcome and keep the old
// input sequence, so the new client's inputs were dropped as stale).
#include <catch2/catch.hpp>

#include "harness.hpp"
#include "fts/protocol/client.hpp"
#include "fts/protocol/server.hpp"

using namespace fts::protocol;

TEST_CASE("Reconnect: a restarted client on the same address is taken back with fresh state", "[protocol][reconnect]") {
  ServerEndpoint server(test::one_room(ServerConfig{}, server));
  std::uint64_t now = 1000;
  const Address addr = "10.0.0.2:7000";
  auto pump = [&](ClientEndpoint& c) {
    for (auto& d : c.take_datagrams()) server.receive(addr, d, now);
    for (auto& o : server.take_datagrams()) c.receive(o.bytes, now);
  };
  ClientConfig cc;
  cc.name = "ann";
  ClientEndpoint first(cc);
  first.connect(now);
  for (int i = 0; i < 20 && first.state() != ClientState::connected; ++i, now += 10) pump(first);
  REQUIRE(first.state() == ClientState::connected);
  for (int i = 0; i < 50; ++i, now += 10) {
    first.send_input({0, 1, 0, false}, now);
    pump(first);
  }
  server.take_inputs();
  server.take_events();
  const std::uint32_t player = first.welcome()->player_id;

  // The process dies without a bye; a new one starts at once from the same address.
  cc.token = first.welcome()->token;
  ClientEndpoint second(cc);
  second.connect(now);
  for (int i = 0; i < 20 && second.state() != ClientState::connected; ++i, now += 10) pump(second);
  REQUIRE(second.state() == ClientState::connected);
  CHECK(second.welcome()->player_id == player);
  CHECK(second.welcome()->reconnected);
  for (int i = 0; i < 5; ++i, now += 10) {
    second.send_input({0, -1, 0, false}, now);
    pump(second);
  }
  const auto inputs = server.take_inputs();
  REQUIRE_FALSE(inputs.empty());  // the new sequence (1, 2, ...) is accepted
  CHECK(inputs.back().frame.move_x == -1);
}
