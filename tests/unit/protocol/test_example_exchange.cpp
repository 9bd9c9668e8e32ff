// Prints the annotated example of PROTOCOL.md: fts_protocol_tests "[.example]"
#include <catch2/catch.hpp>

#include <cstdio>

#include "harness.hpp"
#include "samples.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {
// A session's datagram is sealed (PROTOCOL.md 5.7): printed as its opened payload.
void print(const char* direction, const std::vector<std::uint8_t>& bytes, const ClientEndpoint& client) {
  const auto header = read_header(bytes);
  REQUIRE(header.ok());
  const bool sealed = header->session != 0;
  std::string payload(bytes.begin() + kHeaderBytes, bytes.end());
  if (sealed) {
    SealedChannel channel = channel_of(client, direction[0] == 'C');
    std::vector<std::uint8_t> plain;
    REQUIRE(!channel.open(*header, bytes, plain));
    payload.assign(plain.begin(), plain.end());
  }
  const Header& h = *header;
  std::printf("%s %zu bytes  header{version %u, encoding %s, session %u, seq %u, ack %u, ack_bits %08x, ack_delay %u}%s\n",
              direction, bytes.size(), h.version, h.encoding == Encoding::json ? "json" : "msgpack",
              h.session, h.sequence, h.ack, h.ack_bits, h.ack_delay_ms,
              sealed ? "  sealed, opened:" : "");
  std::printf("%s\n\n", payload.c_str());
}
}  // namespace

TEST_CASE("example exchange", "[.example]") {
  ServerConfig config = test_server_config();
  ServerEndpoint server(one_room(config, server));
  ClientConfig cc;
  cc.encoding = Encoding::json;
  cc.name = "ann";
  cc.nonce = 0x5eed0fa11c0ffee5;  // normally random per connection attempt
  ClientEndpoint client(cc);
  const std::string addr = "192.0.2.7:40000";
  std::uint64_t now = 1000;
  auto pump = [&] {
    for (auto& b : client.take_datagrams()) {
      print("C->S", b, client);
      server.receive(addr, b, now);
    }
    for (auto& o : server.take_datagrams()) {
      print("S->C", o.bytes, client);
      client.receive(o.bytes, now);
    }
  };
  client.connect(now);
  for (int i = 0; i < 4; ++i) pump();
  now += 10;
  client.send_input({0, 1, 0, false}, now);
  pump();
  Snapshot s = sample_snapshot(1, 1, 200);
  s.phase = Phase::shop;
  s.events.clear();
  server.send_snapshot(1, s, now);
  pump();
  now += 10;
  client.send_command(CommandOp::buy, 'm', now);
  pump();
  for (auto& pc : server.take_commands())
    server.send_result(pc.player_id, pc.command.rid, ResultCode::ok, "bought mass: 41 -> 42", now);
  server.update(now);  // results go out with the next update, batched
  pump();
  now += 40;
  s = advance(s, 5, 0.05);
  s.players[0].coins -= 36;
  s.players[0].mass += 1;
  s.players[0].prices[0] += 3;
  s.events.push_back({1, 202, EventKind::purchase, 1, 'm', 36});
  server.send_snapshot(1, s, now);
  pump();
}
