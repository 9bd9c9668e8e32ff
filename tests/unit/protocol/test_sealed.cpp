// Sealed packets (issue 12, PROTOCOL.md 5.7): the golden vectors of the framing, and a
// forged, a tampered and a replayed datagram each dropped and counted with no state
// change. Time is stepped by hand over in-memory links.
#include <catch2/catch.hpp>

#include "fts/protocol/cookie.hpp"
#include "harness.hpp"
#include "key_samples.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

const std::vector<std::uint8_t> kPing = {'[', '{', '"', 't', '"', ':', '"', 'p', 'i', 'n', 'g', '"', '}', ']'};

Header vector_header(std::uint16_t seq, std::uint16_t ack, std::uint16_t delay) {
  Header h;
  h.version = 3;
  h.encoding = Encoding::json;
  h.session = 0x0a0b0c0d;
  h.sequence = seq;
  h.ack = ack;
  h.ack_delay_ms = delay;
  return h;
}

// A connected client, and the server's view of it.
struct Connected {
  Harness h;
  Peer* p = nullptr;
  explicit Connected(ServerConfig config = test_server_config()) : h(std::move(config)) {
    ClientConfig c;
    c.name = "ann";
    c.encoding = Encoding::json;
    p = &h.add_client(c);
    p->client.connect(h.now);
    REQUIRE(h.run_until([&] { return p->client.state() == ClientState::connected; }, 1000));
    h.run_until([] { return false; }, h.now + 50);
    h.server.take_inputs();
  }
  SessionInfo info() const { return h.server.sessions().at(0); }
  // The client's next datagram (an input with a key down), not yet delivered.
  std::vector<std::uint8_t> next_input() {
    p->client.take_datagrams();
    p->client.send_input(InputFrame{0, 1, 0, true}, h.now);
    auto out = p->client.take_datagrams();
    REQUIRE(out.size() == 1);
    return out[0];
  }
  // The ack fields of the server's next datagram (what its AckWindow holds).
  std::pair<std::uint16_t, std::uint32_t> server_acks() {
    h.server.take_datagrams();
    h.now += 200;
    h.server.update(h.now);
    auto out = h.server.take_datagrams();
    REQUIRE(!out.empty());
    auto hd = read_header(out.back().bytes, kProtocolVersion);
    REQUIRE(hd);
    return {hd->ack, hd->ack_bits};
  }
};

}  // namespace

TEST_CASE("Sealed: golden vectors (PROTOCOL.md 5.7.5)", "[protocol][sealed]") {
  const KxKeyPair client = kx_keypair_from_seed(seed_from(0x00));
  const KxKeyPair server = kx_keypair_from_seed(seed_from(0x20));
  CHECK(hex(client.public_key) == "0e0216223f147143d32615a91189c288c1728cba3cc5f9f621b1026e03d83129");
  CHECK(hex(server.public_key) == "99f4674ecc87c0b8e712f192b8f49e7442a9376b4875967ababa28471019a93e");
  const SessionKeys ck = *client_session_keys(client, server.public_key);
  const SessionKeys sk = *server_session_keys(server, client.public_key);
  CHECK(hex(ck.tx) == "17821f6861b0f9ac897981c01cca46b711a0afd09010d3694895333903865af2");
  CHECK(hex(sk.tx) == "59f8af2a2061b2e35fd1cbfb708efd27a85c9924e6b83932e8a67c901a9998cb");
  CHECK(ck.tx == sk.rx);
  CHECK(ck.rx == sk.tx);

  SealedChannel s(sk, SealDirection::server_to_client, SealDirection::client_to_server);
  SealedChannel c(ck, SealDirection::client_to_server, SealDirection::server_to_client);
  std::vector<std::uint8_t> out;
  s.seal(vector_header(1, 0, 0), kPing, out);
  CHECK(hex(out) ==
        "465453500003000a0b0c0d00010000000000000000"
        "378ed4db2dd054b6230e0b5b0019219b7b2634477f9810a703b3097dc27e");
  std::vector<std::uint8_t> plain;
  CHECK(!c.open(*read_header(out, 3), out, plain));
  CHECK(plain == kPing);

  // The client's sequence wrapped once (65535 -> 1): extended sequence 65537.
  std::vector<std::uint8_t> skipped, wrapped;
  c.seal(vector_header(65535, 1, 3), kPing, skipped);
  c.seal(vector_header(1, 1, 3), kPing, wrapped);
  CHECK(hex(wrapped) ==
        "465453500003000a0b0c0d00010001000000000003"
        "d825f86b42d7c4dd77d7739e15609d8f5dc6b8bf3595670d96db32e9a099");
  CHECK(!s.open(*read_header(skipped, 3), skipped, plain));
  CHECK(!s.open(*read_header(wrapped, 3), wrapped, plain));
  CHECK(plain == kPing);

  const std::string token = "0123456789abcdef0123456789abcdef";
  const std::string box = seal_hello_token(ck, client.public_key, token);
  CHECK(box ==
        "42d9e71714d2ea27a1fe7f940c6e93cadc1412190673465631a36f0a08cb0312"
        "bd367ef0d6350cb38c2507db15a2f231");
  CHECK(open_hello_token(sk, client.public_key, box) == token);
  CHECK(!open_hello_token(sk, server.public_key, box));  // another key as associated data
}

TEST_CASE("Sealed: extended sequences and the replay window", "[protocol][sealed]") {
  CHECK(extend_sequence(5, 0) == 5);
  CHECK(extend_sequence(1, 65535) == 65537);
  CHECK(extend_sequence(65535, 65537) == 65535);
  CHECK(extend_sequence(40000, 70000) == 40000);
  CHECK(extend_sequence(100, 3 * 65536 + 60000) == 4 * 65536 + 100);

  const SessionKeys k{seed_from(1), seed_from(2)};
  const SessionKeys peer{k.tx, k.rx};
  SealedChannel tx(k, SealDirection::client_to_server, SealDirection::server_to_client);
  SealedChannel rx(peer, SealDirection::server_to_client, SealDirection::client_to_server);
  std::vector<std::vector<std::uint8_t>> sent(100);
  for (std::uint16_t i = 1; i < 100; ++i) tx.seal(vector_header(i, 0, 0), kPing, sent[i]);
  std::vector<std::uint8_t> plain;
  auto open = [&](std::uint16_t i) { return rx.open(*read_header(sent[i], 3), sent[i], plain); };
  CHECK(!open(10));
  CHECK(!open(9));   // reordered: fine
  CHECK(open(9) == Reject::replayed);
  CHECK(!open(80));
  CHECK(!open(17));  // 63 behind: still in the window
  CHECK(open(16) == Reject::replayed);  // 64 behind: too old
  CHECK(open(80) == Reject::replayed);
  CHECK(rx.drops().replayed == 3);
  CHECK(rx.drops().forged == 0);
}

TEST_CASE("Sealed: a forged datagram is dropped and counted, nothing changes", "[protocol][sealed]") {
  Connected c;
  const auto good = c.next_input();
  c.h.server.receive(c.p->address, good, c.h.now);
  REQUIRE(c.h.server.take_inputs().size() == 1);
  const auto acks = c.server_acks();
  const auto before = c.info();

  // The victim's address and session id, a sequence 30 000 ahead, a buy and a ready in
  // clear, and 16 bytes where a tag would be.
  Header h = *read_header(good, kProtocolVersion);
  h.sequence = static_cast<std::uint16_t>(h.sequence + 30000);
  auto forged = encode_datagram(h, {Command{1, CommandOp::buy, 'm', {}, {}}, Command{2, CommandOp::ready, 0, {}, {}}});
  forged.resize(forged.size() + kSealTagBytes, 0);
  c.h.server.receive(c.p->address, forged, c.h.now);

  CHECK(c.h.server.rejects()[Reject::forged] == 1);
  CHECK(c.info().sealed_drops.forged == 1);
  CHECK(c.h.server.take_commands().empty());
  CHECK(c.h.server.take_inputs().empty());
  CHECK(c.server_acks() == acks);
  CHECK(c.info().rtt_ms == before.rtt_ms);
  CHECK(c.info().rate_limited == before.rate_limited);
  // The real client's next datagram is not made stale by the forged sequence.
  c.h.server.receive(c.p->address, c.next_input(), c.h.now);
  CHECK(c.h.server.take_inputs().size() == 1);
  CHECK(c.h.server.rejects()[Reject::stale] == 0);
}

TEST_CASE("Sealed: a tampered datagram is dropped and counted, nothing changes", "[protocol][sealed]") {
  Connected c;
  const auto good = c.next_input();
  const auto acks = c.server_acks();
  std::uint64_t forged = 0;
  // A flipped bit anywhere: in the header (associated data), the ciphertext or the tag.
  for (std::size_t at : {std::size_t{13}, std::size_t{19}, kHeaderBytes + 2, good.size() - 1}) {
    auto bad = good;
    bad[at] ^= 0x01;
    c.h.server.receive(c.p->address, bad, c.h.now);
    CHECK(c.h.server.rejects()[Reject::forged] == ++forged);
  }
  // Cut short: a tag that does not verify; shorter than a header and a tag: truncated,
  // no tag to check (PROTOCOL.md 5.7.2), and not a drop of the sealed channel.
  c.h.server.receive(c.p->address, std::span(good).first(good.size() - 1), c.h.now);
  const auto truncated = c.h.server.rejects()[Reject::truncated];
  c.h.server.receive(c.p->address, std::span(good).first(kHeaderBytes + kSealTagBytes - 1), c.h.now);
  CHECK(c.h.server.rejects()[Reject::truncated] == truncated + 1);
  CHECK(c.info().sealed_drops.forged == forged + 1);
  CHECK(c.h.server.take_inputs().empty());
  CHECK(c.server_acks() == acks);
  // The untouched datagram still opens afterwards.
  c.h.server.receive(c.p->address, good, c.h.now);
  CHECK(c.h.server.take_inputs().size() == 1);
}

TEST_CASE("Sealed: a replayed datagram is dropped and counted, nothing changes", "[protocol][sealed]") {
  Connected c;
  c.p->client.take_datagrams();
  const std::uint32_t rid = c.p->client.send_command(CommandOp::buy, 'm', c.h.now);
  REQUIRE(rid != 0);
  const auto buy = c.p->client.take_datagrams().at(0);
  c.h.server.receive(c.p->address, buy, c.h.now);
  REQUIRE(c.h.server.take_commands().size() == 1);
  const auto acks = c.server_acks();

  for (int i = 0; i < 3; ++i) c.h.server.receive(c.p->address, buy, c.h.now + 10 * i);
  CHECK(c.h.server.rejects()[Reject::replayed] == 3);
  CHECK(c.info().sealed_drops.replayed == 3);
  CHECK(c.h.server.take_commands().empty());
  CHECK(c.server_acks() == acks);

  // From another address it is not even opened (the session is bound to its address).
  c.h.server.receive("10.6.6.6:5000", buy, c.h.now);
  CHECK(c.h.server.rejects()[Reject::address_mismatch] == 1);
}

TEST_CASE("Sealed: the client drops forged and replayed server datagrams", "[protocol][sealed]") {
  Connected c;
  c.h.server.update(c.h.now + 200);
  auto out = c.h.server.take_datagrams();
  REQUIRE(!out.empty());
  const auto real = out.back().bytes;
  auto forged = real;
  forged[kHeaderBytes] ^= 0x40;
  c.p->client.receive(forged, c.h.now);
  c.p->client.receive(real, c.h.now);
  c.p->client.receive(real, c.h.now);
  CHECK(c.p->client.sealed_drops().forged == 1);
  CHECK(c.p->client.sealed_drops().replayed == 1);
  CHECK(c.p->client.rejects()[Reject::forged] == 1);
  CHECK(c.p->client.state() == ClientState::connected);
  // A forged error in clear does not end a connected session either.
  Header h = *read_header(real, kProtocolVersion);
  h.session = 0;
  c.p->client.receive(encode_datagram(h, {Error{"kicked", "forged"}}), c.h.now);
  CHECK(c.p->client.state() == ClientState::connected);
}

TEST_CASE("Sealed: the token never travels in clear", "[protocol][sealed]") {
  Connected c;
  const std::string token = c.p->client.welcome()->token;
  REQUIRE(token.size() == 32);
  // A reconnect with the token: nothing either side sends contains it.
  ClientConfig again;
  again.name = "ann";
  again.token = token;
  Peer& q = c.h.add_client(again, {}, "10.0.0.1:6000");
  q.client.connect(c.h.now);
  bool seen = false;
  for (int i = 0; i < 40 && q.client.state() != ClientState::connected; ++i) {
    for (auto& b : q.client.take_datagrams()) {
      seen = seen || std::string(b.begin(), b.end()).find(token) != std::string::npos;
      c.h.server.receive(q.address, b, c.h.now);
    }
    for (auto& o : c.h.server.take_datagrams()) {
      seen = seen || std::string(o.bytes.begin(), o.bytes.end()).find(token) != std::string::npos;
      if (o.to == q.address) q.client.receive(o.bytes, c.h.now);
    }
    c.h.now += 5;
  }
  CHECK(q.client.state() == ClientState::connected);
  CHECK(q.client.welcome()->reconnected);
  CHECK(q.client.welcome()->player_id == c.p->client.welcome()->player_id);
  CHECK(!seen);
}

TEST_CASE("Sealed: token take-overs are rate limited per address", "[protocol][sealed]") {
  ServerConfig config = test_server_config();
  config.takeovers_per_s = 1;
  config.takeover_burst = 2;
  Connected c(config);
  const std::string token = c.p->client.welcome()->token;
  std::vector<std::string> errors;
  for (int i = 0; i < 4; ++i) {
    ClientConfig again;
    again.name = "ann";
    again.token = token;
    Peer& q = c.h.add_client(again, {}, "10.0.0.1:" + std::to_string(7000 + i));
    q.client.connect(c.h.now);
    c.h.run_until([&] { return q.client.state() != ClientState::connecting; }, c.h.now + 100);
    errors.push_back(q.client.error() ? q.client.error()->code : std::string());
  }
  CHECK(errors == std::vector<std::string>{"", "", "rate_limited", "rate_limited"});
  CHECK(c.h.server.rejects()[Reject::takeover_limited] == 2);
}
