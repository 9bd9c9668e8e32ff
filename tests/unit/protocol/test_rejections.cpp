// Every rejection reason: counted, never thrown, never a change of state.
#include <catch2/catch.hpp>

#include <cstring>

#include "fts/protocol/cookie.hpp"
#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

std::vector<std::uint8_t> datagram(const std::string& payload, Encoding enc = Encoding::json,
                                   std::uint32_t session = 0, std::uint16_t sequence = 0) {
  Header h;
  h.encoding = enc;
  h.session = session;
  h.sequence = sequence;
  std::vector<std::uint8_t> out;
  write_header(h, out);
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

// The hellos' key pair (fixed: the test can open what the server seals for it).
KxKeyPair hello_keys() { return kx_keypair_from_seed(std::array<std::uint8_t, 32>{7}); }

std::vector<std::uint8_t> padded_hello(const std::string& cookie, const std::string& token = "") {
  Header h;
  h.encoding = Encoding::json;
  return encode_datagram(h, {Hello{"ann", token, cookie, std::string(600, '.'), "00000000000000a1", "", "",
                                   public_key_hex(hello_keys().public_key)}});
}

Reject decode_error(const std::vector<std::uint8_t>& bytes) {
  auto d = decode_datagram(bytes);
  REQUIRE_FALSE(d.ok());
  return d.error();
}

// A server with one connected client, and a way to check that nothing changed.
struct ConnectedPeer {
  Harness h;
  Peer* peer = nullptr;
  std::uint32_t session = 0;
  std::vector<std::uint8_t> valid;  // a valid datagram of the client, not yet delivered

  ConnectedPeer() {
    peer = &h.add_client(ClientConfig{});
    peer->client.connect(h.now);
    REQUIRE(h.run_until([&] { return peer->client.state() == ClientState::connected; }, 1000));
    h.server.take_events();
    peer->client.take_datagrams();  // the welcome's ack, not needed here
    peer->client.send_input({0, 1, 0, false}, h.now);
    auto out = peer->client.take_datagrams();
    REQUIRE(out.size() == 1);
    valid = out[0];
    session = read_header(valid)->session;
  }

  void expect_rejected(const std::vector<std::uint8_t>& bytes, Reject reason, const std::string& from) {
    const auto before = h.server.rejects()[reason];
    const auto total = h.server.rejects().total();
    const auto sessions = h.server.sessions();
    h.server.receive(from, bytes, h.now);
    CHECK(h.server.rejects()[reason] == before + 1);
    CHECK(h.server.rejects().total() == total + 1);
    CHECK(h.server.take_events().empty());
    CHECK(h.server.take_inputs().empty());
    CHECK(h.server.take_commands().empty());
    const auto after = h.server.sessions();
    REQUIRE(after.size() == sessions.size());
    for (std::size_t i = 0; i < after.size(); ++i) {
      CHECK(after[i].address == sessions[i].address);
      CHECK(after[i].connected == sessions[i].connected);
    }
  }
};

}  // namespace

TEST_CASE("decoder rejections", "[protocol][reject]") {
  SECTION("truncated") {
    CHECK(decode_error({'F', 'T', 'S', 'P', 0}) == Reject::truncated);
    CHECK(decode_error(datagram("")) == Reject::truncated);
  }
  SECTION("oversize") { CHECK(decode_error(datagram(std::string(1200, ' '))) == Reject::oversize); }
  SECTION("wrong protocol id") {
    auto bytes = datagram("[{\"t\":\"ping\"}]");
    bytes[0] = 'X';
    CHECK(decode_error(bytes) == Reject::wrong_protocol_id);
  }
  SECTION("bad version") {
    auto bytes = datagram("[{\"t\":\"ping\"}]");
    bytes[5] = 9;
    CHECK(decode_error(bytes) == Reject::bad_version);
  }
  SECTION("bad flags") {
    auto bytes = datagram("[{\"t\":\"ping\"}]");
    bytes[6] = 0x81;
    CHECK(decode_error(bytes) == Reject::bad_flags);
  }
  SECTION("garbage") {
    CHECK(decode_error(datagram("not json")) == Reject::garbage);
    CHECK(decode_error(datagram("{\"t\":\"ping\"}")) == Reject::garbage);          // not a list
    CHECK(decode_error(datagram("[]")) == Reject::garbage);                        // empty list
    CHECK(decode_error(datagram("[{\"t\":\"cmd\",\"rid\":\"1\",\"op\":\"ready\"}]")) == Reject::garbage);
    CHECK(decode_error(datagram("[{\"t\":\"input\",\"ack\":1}]")) == Reject::garbage);  // field missing
    CHECK(decode_error(datagram("\xc1\x00\xff", Encoding::msgpack)) == Reject::garbage);
    CHECK(decode_error(datagram("[{\"t\":\"ping\"}]", Encoding::msgpack)) == Reject::garbage);
  }
  SECTION("commands the server cannot apply still decode (they are answered, not dropped)") {
    auto one = [](const std::string& json) {
      auto d = decode_datagram(datagram(json));
      REQUIRE(d);
      REQUIRE(d->messages.size() == 1);
      return std::get<Command>(d->messages[0]);
    };
    CHECK(one(R"([{"t":"cmd","rid":1,"op":"buy","item":"z"}])").item == 'z');
    CHECK(one(R"([{"t":"cmd","rid":1,"op":"buy","item":"mm"}])").item == 0);
    CHECK(one(R"([{"t":"cmd","rid":1,"op":"buy"}])").item == 0);
    CHECK(one(R"([{"t":"cmd","rid":1,"op":"dance"}])").op == CommandOp::unknown);
    CHECK(one(R"([{"t":"cmd","rid":0,"op":"ready"}])").rid == 0);
  }
  SECTION("unknown type") { CHECK(decode_error(datagram("[{\"t\":\"teleport\"}]")) == Reject::unknown_type); }
  SECTION("out of range") {
    CHECK(decode_error(datagram("[{\"t\":\"input\",\"ack\":1,\"f\":[[1,5,0,0]]}]")) == Reject::out_of_range);
    CHECK(decode_error(datagram("[{\"t\":\"cmd\",\"rid\":-1,\"op\":\"ready\"}]")) == Reject::out_of_range);
    CHECK(decode_error(datagram("[{\"t\":\"ack\",\"ack\":1,\"f\":[]}]")) == Reject::unknown_type);
    CHECK(decode_error(datagram(R"([{"t":"snap","tick":5,"part":2,"parts":2,"phase":"play","level":1,"balls":[],"players":[]}])")) == Reject::out_of_range);
    CHECK(decode_error(datagram(R"([{"t":"snap","tick":5,"part":0,"parts":1,"phase":"play","level":1,"balls":[],"players":[{"i":1,"c":1000000000000001}]}])")) == Reject::out_of_range);
    CHECK(decode_error(datagram(R"([{"t":"hello","name":"ann","token":"","cookie":"","pad":"","nonce":"12"}])")) == Reject::out_of_range);
    CHECK(decode_error(datagram(R"([{"t":"hello","name":"ann","token":"","cookie":"","pad":""}])")) == Reject::garbage);
    std::string many = "[";
    for (int i = 0; i < 40; ++i) many += std::string(i ? "," : "") + "{\"t\":\"ping\"}";
    CHECK(decode_error(datagram(many + "]")) == Reject::out_of_range);
  }
}

TEST_CASE("server rejections change nothing", "[protocol][reject]") {
  ConnectedPeer c;
  const std::string from = c.peer->address;

  SECTION("decoder failures are counted") {
    c.expect_rejected({1, 2, 3}, Reject::truncated, from);
    c.expect_rejected(std::vector<std::uint8_t>(1300, 0), Reject::oversize, from);
    Header h;
    h.encoding = Encoding::json;
    h.session = c.session;
    h.sequence = 50;
    c.expect_rejected(seal_raw(c.peer->client, h, "[{\"t\":\"zap\"}]"), Reject::unknown_type, from);
    h.sequence = 51;
    c.expect_rejected(seal_raw(c.peer->client, h, "{{{{"), Reject::garbage, from);
    // The same without the keys: not even parsed.
    c.expect_rejected(datagram("[{\"t\":\"zap\",\"x\":\"0123\"}]", Encoding::json, c.session, 52), Reject::forged,
                      from);
    // Shorter than a header and a tag (21 + 16 bytes): cut short, not a forgery (PROTOCOL.md 5.7.2).
    c.expect_rejected(datagram("[{\"t\":\"zap\"}]", Encoding::json, c.session, 53), Reject::truncated, from);
  }
  SECTION("bad version: small requests get no answer") {
    auto bytes = c.valid;
    bytes[5] = 7;
    c.expect_rejected(bytes, Reject::bad_version, from);
    CHECK(c.h.server.take_datagrams().empty());
  }
  SECTION("unpadded hello") {
    Header h;
    h.encoding = Encoding::json;
    c.expect_rejected(encode_datagram(h, {Hello{"eve", "", "", "", "00000000000000e1"}}), Reject::unpadded_hello, "6.6.6.6:1");
    CHECK(c.h.server.take_datagrams().empty());
  }
  SECTION("bad cookie: forged, for another address, expired") {
    c.expect_rejected(padded_hello(std::string(48, 'a')), Reject::bad_cookie, "6.6.6.6:1");
    const std::string cookie = make_cookie(test_key(), "7.7.7.7:1", c.h.now);
    c.expect_rejected(padded_hello(cookie), Reject::bad_cookie, "6.6.6.6:1");
    const std::string old = make_cookie(test_key(), "6.6.6.6:1", c.h.now - 20000);
    c.expect_rejected(padded_hello(old), Reject::bad_cookie, "6.6.6.6:1");
  }
  SECTION("bad token") {
    const std::string cookie = make_cookie(test_key(), "6.6.6.6:1", c.h.now);
    c.expect_rejected(padded_hello(cookie, std::string(96, '0')), Reject::bad_token, "6.6.6.6:1");
  }
  SECTION("bad key") {
    const std::string cookie = make_cookie(test_key(), "6.6.6.6:1", c.h.now);
    Header h;
    h.encoding = Encoding::json;
    c.expect_rejected(encode_datagram(h, {Hello{"ann", "", cookie, std::string(600, '.'), "00000000000000a1"}}),
                      Reject::bad_key, "6.6.6.6:1");
  }
  SECTION("unknown session") {
    auto bytes = c.valid;
    bytes[7] ^= 0x55;
    c.expect_rejected(bytes, Reject::unknown_session, from);
  }
  SECTION("a session used from another address") {
    c.expect_rejected(c.valid, Reject::address_mismatch, "6.6.6.6:1");
  }
  SECTION("unexpected: a server message sent to the server") {
    Header h;
    h.encoding = Encoding::json;
    h.session = c.session;
    h.sequence = 77;
    Welcome w;
    w.player_id = 1;
    c.expect_rejected(seal_as(c.peer->client, h, {w}), Reject::unexpected, from);
    h.session = 0;
    c.expect_rejected(encode_datagram(h, {Ping{}}), Reject::unexpected, from);
  }
  SECTION("replayed: a duplicate datagram") {
    c.h.server.receive(from, c.valid, c.h.now);
    REQUIRE(c.h.server.take_inputs().size() == 1);
    c.expect_rejected(c.valid, Reject::replayed, from);
  }
  SECTION("server full: every session slot taken") {
    ServerConfig config = test_server_config();
    config.max_sessions_total = 1;
    ServerEndpoint server(one_room(config, server));
    const auto hello = [&](const std::string& addr) {
      server.receive(addr, padded_hello(""), 1000);
      auto out = server.take_datagrams();
      REQUIRE(out.size() == 1);
      auto d = decode_datagram(out[0].bytes);
      REQUIRE(d.ok());
      server.receive(addr, padded_hello(std::get<Challenge>(d->messages[0]).cookie), 1000);
    };
    hello("1.1.1.1:1");
    server.take_datagrams();
    hello("2.2.2.2:2");
    CHECK(server.rejects()[Reject::server_full] == 1);
    CHECK(server.sessions().size() == 1);
  }
}

TEST_CASE("before the handshake no reply is larger than its request", "[protocol][reject]") {
  ServerEndpoint server(one_room(test_server_config(), server));
  const auto hello = padded_hello("");
  REQUIRE(hello.size() >= kMinHelloBytes);
  server.receive("1.1.1.1:1", hello, 1000);
  auto out = server.take_datagrams();
  REQUIRE(out.size() == 1);
  CHECK(out[0].bytes.size() <= hello.size());
  auto challenge = decode_datagram(out[0].bytes);
  REQUIRE(challenge.ok());
  const auto hello2 = padded_hello(std::get<Challenge>(challenge->messages[0]).cookie);
  server.receive("1.1.1.1:1", hello2, 1000);
  out = server.take_datagrams();
  REQUIRE(out.size() == 1);
  CHECK(out[0].bytes.size() <= hello2.size());
  // The welcome is sealed: it opens with the keys of the hello's key pair.
  const auto server_key = parse_public_key(std::get<Challenge>(challenge->messages[0]).key);
  REQUIRE(server_key);
  SealedChannel channel(*client_session_keys(hello_keys(), *server_key), SealDirection::client_to_server,
                        SealDirection::server_to_client);
  std::vector<std::uint8_t> plain;
  auto welcome = open_sealed(channel, out[0].bytes, kProtocolVersion, plain);
  REQUIRE(welcome.ok());
  CHECK(std::holds_alternative<Welcome>(welcome->messages[0]));
}

TEST_CASE("client rejections", "[protocol][reject]") {
  ConnectedPeer c;
  ClientEndpoint& client = c.peer->client;
  SECTION("a datagram for another session") {
    Header h;
    h.session = c.session + 1;
    h.sequence = 9;
    client.receive(encode_datagram(h, {Ping{}}), c.h.now);
    CHECK(client.rejects()[Reject::unknown_session] == 1);
    CHECK(client.state() == ClientState::connected);
  }
  SECTION("a client message sent to a client") {
    auto sessions = c.h.server.sessions();
    Header h;
    h.session = read_header(c.valid)->session;
    h.sequence = 999;
    client.receive(seal_as(client, h, {Command{1, CommandOp::ready, 0, {}, {}}}, true), c.h.now);
    CHECK(client.rejects()[Reject::unexpected] == 1);
  }
  SECTION("garbage") {
    Header h;
    h.encoding = Encoding::json;
    h.session = c.session;
    h.sequence = 500;
    client.receive(seal_raw(client, h, "]]", true), c.h.now);
    CHECK(client.rejects()[Reject::garbage] == 1);
    CHECK(client.state() == ClientState::connected);
  }
}

TEST_CASE("cookies", "[protocol][cookie]") {
  const ServerKey key = test_key();
  const std::string cookie = make_cookie(key, "1.2.3.4:5", 5000);
  CHECK(cookie.size() == 48);
  CHECK(cookie == make_cookie(key, "1.2.3.4:5", 5000));  // deterministic with the key
  CHECK(check_cookie(key, "1.2.3.4:5", cookie, 5000, 10000) == CookieCheck::ok);
  CHECK(check_cookie(key, "1.2.3.4:5", cookie, 15000, 10000) == CookieCheck::ok);
  CHECK(check_cookie(key, "1.2.3.4:5", cookie, 15001, 10000) == CookieCheck::expired);
  CHECK(check_cookie(key, "1.2.3.4:6", cookie, 5000, 10000) == CookieCheck::forged);
  ServerKey other = key;
  other[0] ^= 1;
  CHECK(check_cookie(other, "1.2.3.4:5", cookie, 5000, 10000) == CookieCheck::forged);
  std::string tampered = cookie;
  tampered[15] = tampered[15] == '0' ? '1' : '0';  // a later issue time
  CHECK(check_cookie(key, "1.2.3.4:5", tampered, 5000, 10000) == CookieCheck::forged);
  CHECK(derive_token(key, 1) != derive_token(key, 2));
  CHECK(derive_session_id(key, 1) != 0);
}
