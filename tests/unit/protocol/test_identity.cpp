// A player's identity in the hello (issue 41, PROTOCOL.md 5.8): the test vector of the
// document, the server's fingerprint of a proven identity, a box that does not verify
// refused, a guest without one, the identity file's text, and an identity taking its
// player back without a token (a client that lost it: another machine, a day later).
#include <catch2/catch.hpp>

#include "harness.hpp"
#include "fts/protocol/client.hpp"
#include "fts/protocol/cookie.hpp"
#include "fts/protocol/identity.hpp"
#include "fts/protocol/server.hpp"
#include "key_samples.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

// One server and clients on their own addresses, stepped by hand.
struct IdentityRig {
  ServerEndpoint server{test::one_room(ServerConfig{}, server)};
  std::uint64_t now = 1000;
  void pump(ClientEndpoint& c, const Address& addr) {
    for (auto& d : c.take_datagrams()) server.receive(addr, d, now);
    for (auto& o : server.take_datagrams())
      if (o.to == addr) c.receive(o.bytes, now);
  }
  void settle(ClientEndpoint& c, const Address& addr) {
    for (int i = 0; i < 30 && c.state() == ClientState::connecting; ++i, now += 10) pump(c, addr);
  }
  void play(ClientEndpoint& c, const Address& addr) {
    for (int i = 0; i < 10; ++i, now += 10) {
      c.send_input({0, 1, 0, false}, now);
      pump(c, addr);
    }
  }
};

ClientConfig with_identity(const std::string& name, std::optional<Identity> id) {
  ClientConfig c;
  c.name = name;
  c.identity = std::move(id);
  return c;
}

}  // namespace

TEST_CASE("Identity: the test vector (PROTOCOL.md 5.8.3)", "[protocol][identity][sealed]") {
  const KxKeyPair client = kx_keypair_from_seed(seed_from(0x00));
  const KxKeyPair server = kx_keypair_from_seed(seed_from(0x20));
  const SessionKeys ck = *client_session_keys(client, server.public_key);
  const SessionKeys sk = *server_session_keys(server, client.public_key);
  const Identity id = identity_from_seed(seed_from(0x40));
  const std::string cookie = "00000000000030390123456789abcdef0123456789abcdef";
  CHECK(hex(id.public_key) == "2543b92ff1095511476adc8369db6ddc933665a11978dda1404ee1066ca9559d");
  CHECK(fingerprint(id) == "0e934e02183f97e0cd83ad10d6c4be5a");
  const auto transcript = identity_transcript(cookie, client.public_key, server.public_key);
  REQUIRE(transcript);
  CHECK(transcript->size() == 103);
  const std::string box = seal_hello_identity(id, ck, client.public_key, server.public_key, cookie);
  CHECK(box ==
        "e16a2caac55b7fd0dd8d4663428a1bd1487aa62783cc4ee7e8b50f19c0d3214b2eeaef8066502552311a4e7e2168d3d4"
        "5867ebdb211b8b4a29bb199575318aa747550b255c8ca20bed3fcc5e8c117ac2d9f026a45bc6a8f7019138cec0239ef1"
        "839d24d543f5947eac7038417dd2d817");
  CHECK(box.size() == kSealedIdentityHex);
  CHECK(open_hello_identity(sk, client.public_key, server.public_key, cookie, box) == fingerprint(id));
  // Another handshake's cookie (a replayed proof), another server, a flipped bit: refused.
  CHECK_FALSE(open_hello_identity(sk, client.public_key, server.public_key,
                                  "00000000000030390123456789abcdef0123456789abcdee", box));
  CHECK_FALSE(open_hello_identity(sk, client.public_key, client.public_key, cookie, box));
  std::string flipped = box;
  flipped[10] = flipped[10] == '0' ? '1' : '0';
  CHECK_FALSE(open_hello_identity(sk, client.public_key, server.public_key, cookie, flipped));
  CHECK_FALSE(open_hello_identity(sk, client.public_key, server.public_key, cookie, ""));
}

TEST_CASE("Identity: the file's text reads back - anything else does not", "[protocol][identity]") {
  const Identity id = identity_from_seed(seed_from(0x40));
  const std::string text = identity_file_text(id);
  CHECK(text == "fts-identity-1 404142434445464748494a4b4c4d4e4f505152535455565758595a5b5c5d5e5f\n");
  const auto back = parse_identity_file(text);
  REQUIRE(back);
  CHECK(back->public_key == id.public_key);
  CHECK_FALSE(parse_identity_file("fts-identity-1 4041"));
  CHECK_FALSE(parse_identity_file("ssh-ed25519 AAAA"));
  CHECK(new_identity().public_key != new_identity().public_key);
}

TEST_CASE("Identity: the server knows a proven player by its fingerprint - a guest has none",
          "[protocol][identity][handshake]") {
  IdentityRig r;
  const Identity id = new_identity();
  ClientEndpoint ann(with_identity("ann", id)), bob(with_identity("bob", std::nullopt));
  ann.connect(r.now);
  bob.connect(r.now);
  r.settle(ann, "10.0.0.1:1");
  r.settle(bob, "10.0.0.2:1");
  REQUIRE(ann.state() == ClientState::connected);
  REQUIRE(bob.state() == ClientState::connected);
  CHECK(r.server.session_identity(ann.welcome()->player_id) == fingerprint(id));
  CHECK(r.server.session_identity(bob.welcome()->player_id).empty());
  std::map<std::string, std::string> by_name;
  for (const auto& e : r.server.take_events())
    if (e.kind == ServerEvent::Kind::connected) by_name[e.name] = e.identity;
  CHECK(by_name.at("ann") == fingerprint(id));
  CHECK(by_name.at("bob").empty());
}

TEST_CASE("Identity: a proof that does not verify is refused bad_identity", "[protocol][identity][handshake]") {
  IdentityRig r;
  ClientEndpoint eve(with_identity("eve", new_identity()));
  eve.connect(r.now);
  // The challenge arrives; the cookie hello's id is then spoiled on its way.
  r.pump(eve, "10.0.0.3:1");
  auto hellos = eve.take_datagrams();
  REQUIRE(hellos.size() == 1);
  auto decoded = decode_datagram(hellos[0], kProtocolVersion);
  REQUIRE(decoded);
  Hello h = std::get<Hello>(decoded->messages.at(0));
  REQUIRE(h.id.size() == kSealedIdentityHex);
  h.id[0] = h.id[0] == 'a' ? 'b' : 'a';
  r.server.receive("10.0.0.3:1", encode_datagram(decoded->header, {h}), r.now);
  for (auto& o : r.server.take_datagrams()) eve.receive(o.bytes, r.now);
  CHECK(eve.state() == ClientState::refused);
  REQUIRE(eve.error());
  CHECK(eve.error()->code == "bad_identity");
  CHECK(r.server.rejects()[Reject::bad_identity] == 1);
  CHECK(r.server.sessions().empty());
}

TEST_CASE("Identity: a returning identity without its token is the same player", "[protocol][identity][reconnect]") {
  IdentityRig r;
  const Identity id = new_identity();
  ClientEndpoint first(with_identity("ann", id));
  first.connect(r.now);
  r.settle(first, "10.0.0.1:1");
  REQUIRE(first.state() == ClientState::connected);
  r.play(first, "10.0.0.1:1");
  const std::uint32_t player = first.welcome()->player_id;
  first.disconnect(r.now);  // bye: its seat is free, its progress kept
  r.pump(first, "10.0.0.1:1");
  r.server.take_events();

  // Another machine (another address), no token: the identity takes the player back.
  ClientEndpoint again(with_identity("ann", id));
  again.connect(r.now);
  r.settle(again, "10.0.0.9:5");
  REQUIRE(again.state() == ClientState::connected);
  CHECK(again.welcome()->player_id == player);
  CHECK(again.welcome()->reconnected);
  CHECK(again.welcome()->token.size() == 32);
  bool reconnected = false;
  for (const auto& e : r.server.take_events())
    reconnected |= e.kind == ServerEvent::Kind::reconnected && e.player_id == player && e.reason == "identity";
  CHECK(reconnected);

  // Someone else's identity (or none) is someone new.
  ClientEndpoint other(with_identity("ann", new_identity()));
  other.connect(r.now);
  r.settle(other, "10.0.0.7:5");
  REQUIRE(other.state() == ClientState::connected);
  CHECK(other.welcome()->player_id != player);
  CHECK_FALSE(other.welcome()->reconnected);
}

TEST_CASE("Identity: a restored player (--resume) is taken back by its identity with a new token",
          "[protocol][identity][restore]") {
  IdentityRig r;
  const Identity id = new_identity();
  RestoredSession rs;
  rs.player_id = 7;
  rs.name = "ann";
  rs.token_verifier = token_verifier("0123456789abcdef0123456789abcdef");
  rs.identity = fingerprint(id);
  REQUIRE(r.server.restore_session(rs, r.now));
  ClientEndpoint back(with_identity("ann", id));
  back.connect(r.now);
  r.settle(back, "10.0.0.1:1");
  REQUIRE(back.state() == ClientState::connected);
  CHECK(back.welcome()->player_id == 7);
  CHECK(back.welcome()->reconnected);
  CHECK(back.welcome()->token.size() == 32);
  CHECK(r.server.session_verifier(7) == token_verifier(back.welcome()->token));
}
