// Fair slots (issue 12): sessions per host, the hello rate per host, the idle time-out
// (paused while the players cannot act), and sessions that never played hold no slot.
// Time is stepped by hand over in-memory links.
#include <catch2/catch.hpp>

#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {


std::vector<std::uint8_t> padded_hello() {
  Header h;
  h.encoding = Encoding::json;
  return encode_datagram(h, {Hello{"ann", "", "", std::string(600, '.'), "00000000000000a1"}});
}

std::size_t released(Harness& h, const std::string& reason) {
  std::size_t n = 0;
  for (const auto& e : h.server.take_events()) n += e.kind == ServerEvent::Kind::released && e.reason == reason;
  return n;
}

}  // namespace

TEST_CASE("Slots: a host past its session cap gets address_full, others still join", "[protocol][slots]") {
  Harness h;  // 8 players, 4 per host
  std::vector<Peer*> same;
  for (int port = 1; port <= 6; ++port)
    same.push_back(&h.add_client(named("s" + std::to_string(port)), {}, "203.0.113.5:" + std::to_string(4000 + port)));
  Peer& other = h.add_client(named("real"), {}, "198.51.100.1:5000");
  for (auto* p : same) p->client.connect(h.now);
  other.client.connect(h.now);
  h.run_until([&] { return false; }, h.now + 1000);
  int joined = 0, refused = 0;
  for (auto* p : same) {
    if (connected(*p)) ++joined;
    if (p->client.state() == ClientState::refused) {
      ++refused;
      CHECK(p->client.error()->code == "address_full");
    }
  }
  CHECK(joined == 4);
  CHECK(refused == 2);
  CHECK(connected(other));
  CHECK(h.server.rejects()[Reject::address_full] >= 2);
}

TEST_CASE("Slots: the address_full refusal is smaller than the hello", "[protocol][slots]") {
  ServerConfig config = test_server_config();
  config.max_sessions_per_address = 0;
  ServerEndpoint server(one_room(config, server));
  ClientEndpoint c(named("ann"));
  c.connect(100);
  for (int i = 0; i < 3; ++i)
    for (auto& d : c.take_datagrams()) {
      server.receive("203.0.113.5:1", d, 100);
      for (auto& o : server.take_datagrams()) {
        CHECK(o.bytes.size() < d.size());
        c.receive(o.bytes, 100);
      }
    }
  REQUIRE(c.state() == ClientState::refused);
  CHECK(c.error()->code == "address_full");
  CHECK(server.sessions().empty());
}

TEST_CASE("Slots: hellos from one host are rate limited", "[protocol][slots]") {
  ServerEndpoint server(one_room(test_server_config(), server));  // 10/s, burst 10
  const auto hello = padded_hello();
  for (int port = 1; port <= 30; ++port) server.receive("203.0.113.5:" + std::to_string(port), hello, 1000);
  CHECK(server.take_datagrams().size() == 10);  // challenges
  CHECK(server.rejects()[Reject::rate_limited] == 20);
  server.receive("198.51.100.1:1", hello, 1000);  // another host is not affected
  CHECK(server.take_datagrams().size() == 1);
  for (int i = 0; i < 5; ++i) server.receive("203.0.113.5:1", hello, 1200);  // 2 tokens back after 200 ms
  CHECK(server.take_datagrams().size() == 2);
}

TEST_CASE("Slots: a session without real input is dropped as idle", "[protocol][slots][idle]") {
  ServerConfig config = test_server_config();
  config.idle_timeout_ms = 3000;
  SECTION("heartbeats alone do not hold the slot") {
    Harness h(config);
    Peer& p = h.add_client(named("ann"));
    p.client.connect(h.now);
    REQUIRE(h.run_until([&] { return connected(p); }, 1000));
    const std::uint64_t from = h.now;
    // Neutral input frames every 100 ms: the 14 B/s slot holder of the issue.
    std::uint32_t t = 0;
    REQUIRE(h.run_until([&] {
      if (++t % 20 == 0) p.client.send_input({0, 0, 0, false}, h.now);
      return p.client.state() == ClientState::refused;
    }, from + 4000));
    CHECK(p.client.error()->code == "idle");
    CHECK(h.now - from >= 2900);
    CHECK(h.server.rejects()[Reject::idle] == 1);
    // Its seat is free, but what it earned is kept for the reconnect window (as a quit).
    CHECK(released(h, "idle") == 0);
    const auto sessions = h.server.sessions();
    REQUIRE(sessions.size() == 1);
    CHECK_FALSE(sessions[0].connected);
  }
  SECTION("a key now and then keeps it") {
    Harness h(config);
    Peer& p = h.add_client(named("ann"));
    p.client.connect(h.now);
    REQUIRE(h.run_until([&] { return connected(p); }, 1000));
    std::uint32_t t = 0;
    h.run_until([&] {
      if (++t % 400 == 0) p.client.send_input({0, 1, 0, false}, h.now);  // every 2 s
      else if (t % 20 == 0) p.client.send_input({0, 0, 0, false}, h.now);
      return false;
    }, h.now + 10000);
    CHECK(connected(p));
    CHECK(h.server.rejects()[Reject::idle] == 0);
  }
  SECTION("never while paused (lobby, shop), and the clock restarts after") {
    Harness h(config);
    h.server.set_idle_paused(1, true);  // one_room's room
    Peer& p = h.add_client(named("ann"));
    p.client.connect(h.now);
    REQUIRE(h.run_until([&] { return connected(p); }, 1000));
    h.run_until([&] { return false; }, h.now + 10000);
    CHECK(connected(p));
    h.server.set_idle_paused(1, false);
    const std::uint64_t from = h.now;
    REQUIRE(h.run_until([&] { return p.client.state() == ClientState::refused; }, from + 4000));
    CHECK(h.now - from >= 2900);
  }
}

TEST_CASE("Slots: a session that never played holds no slot after its time-out", "[protocol][slots][probe]") {
  SECTION("a probe whose bye is lost") {
    Harness h;
    Peer& p = h.add_client(named("probe"));
    p.client.connect(h.now);
    REQUIRE(h.run_until([&] { return connected(p); }, 1000));
    h.server.take_events();
    p.up = LossyLink({1.0, 0, 0, 0, 1});  // the bye and everything after it are lost
    p.client.disconnect(h.now, kProbeByeReason);
    h.run_until([&] { return false; }, h.now + 10100);
    CHECK(released(h, "timeout") == 1);
    CHECK(h.server.sessions().empty());
  }
  SECTION("a player keeps its slot for the reconnect window") {
    Harness h;
    Peer& p = h.add_client(named("ann"));
    p.client.connect(h.now);
    REQUIRE(h.run_until([&] { return connected(p); }, 1000));
    p.client.send_input({0, 1, 0, false}, h.now);
    h.step(h.now + 5);
    h.server.take_events();
    p.up = LossyLink({1.0, 0, 0, 0, 1});
    h.run_until([&] { return false; }, h.now + 10100);
    CHECK(released(h, "timeout") == 0);
    REQUIRE(h.server.sessions().size() == 1);
    CHECK_FALSE(h.server.sessions()[0].connected);
  }
}

TEST_CASE("Slots: a room's counts follow its sessions as they come, quit and go", "[protocol][slots]") {
  // The per-room counts read an index of each room's sessions made again when one comes
  // or goes; a quit or a first input changes flags only, read live.
  Harness h;
  Peer& ann = h.add_client(named("ann"));
  Peer& bob = h.add_client(named("bob"));
  Peer& cid = h.add_client(named("cid"));
  for (Peer* p : {&ann, &bob, &cid}) p->client.connect(h.now);
  REQUIRE(h.run_until([&] { return connected(ann) && connected(bob) && connected(cid); }, 1000));
  CHECK(h.server.seats_in_room(1) == 3);
  CHECK(h.server.sessions_in_room(1) == 3);
  CHECK(h.server.connected_in_room(1).size() == 3);
  CHECK(h.server.holding_in_room(1) == 3);
  CHECK(h.server.seats_in_room(2) == 0);
  CHECK(h.server.sessions_of_room(2).empty());

  ann.client.send_input({0, 1, 0, false}, h.now);  // ann plays, then both ann and bob quit
  h.run_until([] { return false; }, h.now + 50);
  ann.client.disconnect(h.now);
  bob.client.disconnect(h.now);
  h.run_until([] { return false; }, h.now + 50);
  CHECK(h.server.seats_in_room(1) == 1);        // cid's: a quit frees the seat
  CHECK(h.server.sessions_in_room(1) == 3);     // both kept for the reconnect window
  CHECK(h.server.holding_in_room(1) == 2);      // cid connected, ann played; bob holds nothing
  CHECK(h.server.connected_in_room(1) == std::vector<std::uint32_t>{cid.client.welcome()->player_id});
  CHECK(h.server.sessions_of_room(1).size() == 3);
}
