// A room that moves to another server (issue 42, PROTOCOL.md 4.9b): the old server tells
// the room's clients where (`moved`) and lets their sessions go; a client's connection
// follows at once, with its token, and the new server (which restored the sessions from
// the room's journal, as after a restart) takes the same player back. A `moved` that is
// not sealed in the client's session moves nothing.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

#include "fts/protocol/codec.hpp"
#include "fts/protocol/connection.hpp"
#include "fts/protocol/server.hpp"
#include "harness.hpp"

using namespace fts::protocol;

namespace {

ServerConfig moved_keyed(std::uint8_t flip) {
  ServerConfig c = test::test_server_config();
  c.key[0] ^= flip;
  return c;
}

struct MoveRig {
  ServerEndpoint a{test::one_room(moved_keyed(0), a)};
  ServerEndpoint b{test::one_room(moved_keyed(0xff), b)};
  ClientConnection conn{test::named("ann"), /*resume_when_lost=*/true};
  bool on_b = false;  // where the client's datagrams go (the caller follows moved_to())
  std::uint64_t now = 100;

  MoveRig() { conn.connect(now); }
  std::string address() const { return "10.0.0.1:" + std::to_string(5000 + conn.attempt()); }
  void step() {
    now += 5;
    ServerEndpoint& to = on_b ? b : a;
    for (auto& d : conn.endpoint().take_datagrams()) to.receive(address(), d, now);
    for (ServerEndpoint* s : {&a, &b})
      for (auto& out : s->take_datagrams())
        if (out.to == address() && s == &to) conn.endpoint().receive(out.bytes, now);
    conn.update(now);
    a.update(now);
    b.update(now);
  }
  template <class Pred>
  bool run_until(Pred pred, std::uint64_t for_ms) { return test::step_until(*this, pred, for_ms); }
  bool connected() const { return test::welcomed(conn); }
};

}  // namespace

TEST_CASE("Moved: the room's clients follow it to the new server as the same player", "[protocol][moved]") {
  MoveRig rig;
  REQUIRE(rig.run_until([&] { return rig.connected(); }, 2000));
  const std::uint32_t id = rig.conn.endpoint().welcome()->player_id;
  const std::string token = rig.conn.token();
  rig.conn.endpoint().send_input({1, 1, 0, false}, rig.now);
  rig.step();
  (void)rig.a.take_events();

  // The peer restored the room's sessions from its journal (GameHost::adopt_room) ...
  REQUIRE(rig.b.restore_session({id, "ann", rig.a.session_verifier(id), false}, rig.now, 1, "ROOMA"));
  // ... and only then does the old server tell the room's clients.
  CHECK(rig.a.move_room(1, "10.9.9.9:7778", "ROOMA", rig.now) == 1);
  CHECK(rig.a.sessions().empty());
  const auto events = rig.a.take_events();
  REQUIRE(events.size() == 1);
  CHECK(events[0].kind == ServerEvent::Kind::released);
  CHECK(events[0].reason == "moved");
  rig.step();
  CHECK(rig.conn.moves() == 1);
  CHECK(rig.conn.moved_to() == "10.9.9.9:7778");
  CHECK(rig.conn.attempt() == 2);  // a new attempt at once, not a lost connection
  CHECK_FALSE(rig.conn.resuming());

  rig.on_b = true;
  REQUIRE(rig.run_until([&] { return rig.connected(); }, 2000));
  CHECK(rig.conn.endpoint().welcome()->player_id == id);
  CHECK(rig.conn.endpoint().welcome()->reconnected);
  CHECK(rig.conn.endpoint().welcome()->room == "ROOMA");
  CHECK(rig.conn.token() == token);
  CHECK(rig.conn.moves() == 1);  // the two other copies of `moved` went to a closed attempt
}

TEST_CASE("Moved: a move not sealed in the client's session is dropped", "[protocol][moved][sealed]") {
  MoveRig rig;
  REQUIRE(rig.run_until([&] { return rig.connected(); }, 2000));
  // Another client's session keys: what an attacker who is a player of the server holds.
  MoveRig other;
  REQUIRE(other.run_until([&] { return other.connected(); }, 2000));
  // A real header of ann's session (a board the server sends her), with a later sequence.
  const std::uint32_t id = rig.conn.endpoint().welcome()->player_id;
  REQUIRE(rig.a.send_board(id, Leaderboard{1, {}, 0, 0, 0, 0}, rig.now));
  const auto out = rig.a.take_datagrams();
  REQUIRE_FALSE(out.empty());
  Header h = *read_header(out.back().bytes, kProtocolVersion);
  h.sequence = static_cast<std::uint16_t>(h.sequence + 100);
  const auto forged = test::seal_as(other.conn.endpoint(), h, {Moved{"6.6.6.6:7777", "ROOMA"}}, true);
  const auto forged_before = rig.conn.endpoint().sealed_drops().forged;
  rig.conn.endpoint().receive(forged, rig.now);
  rig.step();
  CHECK(rig.conn.endpoint().sealed_drops().forged == forged_before + 1);
  CHECK(rig.conn.moves() == 0);
  CHECK(rig.conn.moved_to().empty());
  CHECK(rig.connected());
  CHECK(rig.conn.attempt() == 1);
}

TEST_CASE("Moved: a room's spectators are told too, and other rooms' sessions stay", "[protocol][moved]") {
  test::Harness h;
  test::Peer& p = h.add_client(test::named("ann"));
  p.client.connect(h.now);
  REQUIRE(h.run_until([&] { return test::connected(p); }, 1000));
  CHECK(h.server.move_room(2, "10.9.9.9:7778", "OTHER", h.now) == 0);  // no session of room 2
  CHECK(h.server.sessions().size() == 1);
  CHECK(h.server.move_room(1, "10.9.9.9:7778", "ROOMA", h.now) == 1);
  REQUIRE(h.run_until([&] { return p.client.moved().has_value(); }, 1000));
  CHECK(p.client.moved()->address == "10.9.9.9:7778");
  CHECK(p.client.moved()->room == "ROOMA");
  CHECK(p.client.state() == ClientState::disconnected);
}

TEST_CASE("Moved: the test vector of PROTOCOL.md 4.9b", "[protocol][moved]") {
  const std::vector<Message> m{Moved{"10.0.0.7:7778", "KWZWC"}};
  std::vector<std::uint8_t> packed;
  append_payload(Encoding::msgpack, m, packed);
  static const char* digits = "0123456789abcdef";
  std::string hex;
  for (auto b : packed) {
    hex += digits[b >> 4];
    hex += digits[b & 15];
  }
  const std::string json = to_json_text(m);
  CHECK(json == R"([{"t":"moved","addr":"10.0.0.7:7778","room":"KWZWC"}])");
  CHECK(hex == "9183a174a56d6f766564a461646472ad31302e302e302e373a37373738a4726f6f6da54b575a5743");
  std::ifstream in(std::string(FTS_SOURCE_DIR) + "/protocol/PROTOCOL.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(doc.find("json     " + json) != std::string::npos);
  CHECK(doc.find("msgpack  " + hex) != std::string::npos);
}
