// A health check's bye frees its slot at once; an ordinary bye holds it for a reconnect.
#include <catch2/catch.hpp>

#include "harness.hpp"
#include "fts/protocol/client.hpp"
#include "fts/protocol/server.hpp"

using namespace fts::protocol;

namespace {
// Connects one client to the server over a perfect in-memory link; returns the events.
std::vector<ServerEvent> connect_then_bye(const std::string& reason) {
  ServerConfig sc;
  ServerEndpoint server(test::one_room(sc, server));
  ClientConfig cc;
  cc.name = "probe";
  ClientEndpoint client(cc);
  std::uint64_t now = 1000;
  client.connect(now);
  std::vector<ServerEvent> events;
  auto pump = [&] {
    for (auto& d : client.take_datagrams()) server.receive("10.0.0.1:9", d, now);
    for (auto& o : server.take_datagrams()) client.receive(o.bytes, now);
    for (auto& e : server.take_events()) events.push_back(e);
  };
  for (int i = 0; i < 20 && client.state() != ClientState::connected; ++i, now += 10) pump();
  REQUIRE(client.state() == ClientState::connected);
  client.disconnect(now, reason);
  pump();
  server.update(now + 100);
  for (auto& e : server.take_events()) events.push_back(e);
  return events;
}
bool has(const std::vector<ServerEvent>& ev, ServerEvent::Kind k) {
  for (const auto& e : ev)
    if (e.kind == k) return true;
  return false;
}
}  // namespace

TEST_CASE("Bye: a probe's slot is freed at once, a player's is held", "[protocol][bye]") {
  const auto probe = connect_then_bye(kProbeByeReason);
  CHECK(has(probe, ServerEvent::Kind::disconnected));
  CHECK(has(probe, ServerEvent::Kind::released));
  const auto quit = connect_then_bye("quit");
  CHECK(has(quit, ServerEvent::Kind::disconnected));
  CHECK_FALSE(has(quit, ServerEvent::Kind::released));
}

TEST_CASE("Bye: a client's reason is cleaned to one the server reads (PROTOCOL.md 4.9)", "[protocol][bye]") {
  // The server drops a bye whose reason is too long or not printable; the client's
  // disconnect() sends what it reads, so the session still ends.
  const auto ended = connect_then_bye("\x1b[2J" + std::string(300, 'x'));
  CHECK(has(ended, ServerEvent::Kind::disconnected));
}
