// The handshake on its own (issue 39, handshake.hpp): what a hello must prove, in the
// order the server checks it, without an endpoint or a session: the cookie of its
// challenge, its name, its key, and the token it brings back, sealed, at its host's
// reconnect rate.
#include <catch2/catch.hpp>

#include "fts/protocol/handshake.hpp"

using namespace fts::protocol;

namespace {

ServerKey key_of(std::uint8_t b) {
  ServerKey k;
  k.fill(b);
  return k;
}

AddressLimits one_reconnect_a_host() {
  AddressLimits::Rates r;
  r.takeovers_per_s = 0;
  r.takeover_burst = 1;
  r.max_hosts = 16;
  return AddressLimits(r);
}

}  // namespace

TEST_CASE("Handshake: a hello is challenged, then proves its address, name, key and token", "[protocol][handshake]") {
  const Handshake hs(key_of(3), 10'000);
  const Address from = "10.0.0.1:5000";
  std::uint64_t now = 1'000;
  Hello hello{"ann", "", "", "", "0123456789abcdef"};

  // No cookie: challenged, nothing counted.
  const auto first = hs.screen(from, hello, now);
  REQUIRE(first);
  CHECK_FALSE(first->counted);
  REQUIRE(first->reply);
  const auto* challenge = std::get_if<Challenge>(&*first->reply);
  REQUIRE(challenge);

  // A cookie made for another address is forged: counted, and no word back.
  Hello moved = hello;
  moved.cookie = challenge->cookie;
  const auto forged = hs.screen("10.0.0.2:5000", moved, now);
  REQUIRE(forged);
  CHECK(forged->counted == Reject::bad_cookie);
  CHECK_FALSE(forged->reply);
  // Past its lifetime: challenged again (and counted).
  const auto expired = hs.screen(from, moved, now + 60'000);
  REQUIRE(expired);
  CHECK(expired->counted == Reject::bad_cookie);
  CHECK(expired->reply);
  // A name a person cannot read.
  Hello bad_name = moved;
  bad_name.name = "a\x01";
  const auto named = hs.screen(from, bad_name, now);
  REQUIRE(named);
  CHECK(named->counted == Reject::out_of_range);
  // The cookie of its own challenge, from its own address: on.
  CHECK_FALSE(hs.screen(from, moved, now));

  // No usable key: refused.
  AddressLimits limits = one_reconnect_a_host();
  const auto keyless = hs.prove(from, moved, limits, now);
  REQUIRE(std::holds_alternative<HelloAnswer>(keyless));
  CHECK(std::get<HelloAnswer>(keyless).counted == Reject::bad_key);

  // A key: the session's keys are the client's, and its sealed token opens to what it sent.
  const KxKeyPair client = kx_random_keypair();
  const auto server_public = parse_public_key(challenge->key);
  REQUIRE(server_public);
  const auto client_keys = client_session_keys(client, *server_public);
  REQUIRE(client_keys);
  moved.key = public_key_hex(client.public_key);
  const std::string token = "00112233445566778899aabbccddeeff";
  moved.token = seal_hello_token(*client_keys, client.public_key, token);
  const auto proof = hs.prove(from, moved, limits, now);
  REQUIRE(std::holds_alternative<ProvenHello>(proof));
  const auto& proven = std::get<ProvenHello>(proof);
  CHECK(proven.token == token);
  CHECK(proven.identity.empty());
  CHECK(proven.keys.rx == client_keys->tx);
  CHECK(proven.keys.tx == client_keys->rx);

  // A second token from the same host at once: past its reconnect rate.
  const auto again = hs.prove(from, moved, limits, now);
  REQUIRE(std::holds_alternative<HelloAnswer>(again));
  CHECK(std::get<HelloAnswer>(again).counted == Reject::takeover_limited);
  // Another host has its own; a token that does not open takes nobody back ("-").
  Hello garbled = moved;
  garbled.token = std::string(96, 'f');
  const auto other = hs.prove("10.0.0.3:5000", garbled, limits, now);
  REQUIRE(std::holds_alternative<ProvenHello>(other));
  CHECK(std::get<ProvenHello>(other).token == "-");
}
