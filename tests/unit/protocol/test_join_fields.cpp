// Rooms on the wire (issue 13, PROTOCOL.md 5.6): the hello's join fields, the welcome's
// room fields and the rooms command round-trip in both encodings; older messages without
// them still decode; a welcome fits in the reply to a padded hello.
#include <catch2/catch.hpp>

#include "fts/protocol/client.hpp"
#include "fts/protocol/codec.hpp"

using namespace fts::protocol;

namespace {

Message round_trip(const Message& m, Encoding enc) {
  Header h;
  h.encoding = enc;
  auto d = decode_datagram(encode_datagram(h, {m}));
  REQUIRE(d.ok());
  REQUIRE(d->messages.size() == 1);
  return d->messages[0];
}

}  // namespace

TEST_CASE("Join fields: hello join/room, welcome room/spectator, cmd rooms round-trip", "[protocol][rooms]") {
  Welcome w;
  w.player_id = 4;
  w.token = std::string(32, 'c');
  w.room = "KXBQT";
  w.spectator = true;
  const std::vector<Message> messages = {Hello{"cat", "", "", "..", "00112233445566ff", "spectate", "KXBQT"},
                                         Hello{"dan", "", "", "..", "00112233445566fe", "create", ""}, w,
                                         Command{4, CommandOp::rooms, 0, {}, {}}};
  for (Encoding enc : {Encoding::json, Encoding::msgpack})
    for (const auto& m : messages) CHECK(round_trip(m, enc) == m);
}

TEST_CASE("Join fields: absent on the wire when empty, so older peers' messages decode", "[protocol][rooms]") {
  Header h;
  h.encoding = Encoding::json;
  const auto bytes = encode_datagram(h, {Hello{"ann", "", "", "", "0123456789abcdef"}});
  const std::string text(bytes.begin(), bytes.end());
  CHECK(text.find("join") == std::string::npos);
  CHECK(text.find("room") == std::string::npos);
  Welcome w;
  w.player_id = 1;
  w.token = std::string(32, 'a');
  const auto wb = encode_datagram(h, {w});
  CHECK(std::string(wb.begin(), wb.end()).find("spectator") == std::string::npos);
  auto m = std::get<Hello>(round_trip(Hello{"ann", "", "", "", "0123456789abcdef"}, Encoding::msgpack));
  CHECK(m.join.empty());
  CHECK(m.room.empty());
}

TEST_CASE("Join fields: the client's hello carries its choice, padded as before", "[protocol][rooms]") {
  ClientConfig c;
  c.name = "eve";
  c.join = "join";
  c.room = "MNPRT";
  for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
    c.encoding = enc;
    ClientEndpoint client(c);
    client.connect(1000);
    auto out = client.take_datagrams();
    REQUIRE(out.size() == 1);
    CHECK(out[0].size() >= kMinHelloBytes);
    auto d = decode_datagram(out[0]);
    REQUIRE(d.ok());
    const auto& hello = std::get<Hello>(d->messages[0]);
    CHECK(hello.join == "join");
    CHECK(hello.room == "MNPRT");
  }
}

TEST_CASE("Join fields: the largest welcome still fits in the reply to a minimal hello", "[protocol][rooms]") {
  Welcome w;
  w.player_id = 4294967295u;
  w.token = std::string(32, 'c');
  w.server_tick = 4294967295u;
  w.timeout_ms = w.reconnect_window_ms = 3600000;
  w.match.arena_width_u = w.match.arena_height_u = 123456.789;
  w.match.frame_s = 0.0333333333333;
  w.match.multiplier_upgrade_factor = w.match.bank_interest_factor = 1.1000000000001;
  // The friction of issue 36's host (a configuration whose welcome would not fit is
  // refused at start: test_welcome_config.cpp).
  w.match.friction_per_frame = 0.95;
  w.match.tick_rate_hz = 1000;
  w.room = "KXBQT";
  w.spectator = true;
  for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
    Header h;
    h.encoding = enc;
    h.session = 0xFFFFFFFF;
    CHECK(encode_datagram(h, {w}).size() <= kMinHelloBytes);
  }
}
