// Garbage rejection rate of ServerEndpoint::receive (issue 12), one core. A benchmark:
// figures are printed for BENCHMARKS.md, never asserted on time. Run:
// fts-protocol-bench "[garbage]".
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <random>

#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

struct Sample {
  Address from;
  std::vector<std::uint8_t> bytes;
};

std::vector<std::uint8_t> with_header(std::uint32_t session, const std::string& payload) {
  Header h;
  h.encoding = Encoding::json;
  h.session = session;
  h.sequence = session ? 7 : 0;
  std::vector<std::uint8_t> out;
  write_header(h, out);
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

// A live session's address and id, for forged datagrams that reach the tag check.
struct Victim {
  Address from;
  std::uint32_t session = 0;
};

// kind: 0 random bytes, 1 our header + random session + junk, 2 deep nesting (hello
// sized), 3 session 0 + truncated JSON, 4 MessagePack that lies about its sizes, 5 a
// live session's address, id and a fresh sequence, random ciphertext and tag (each one
// costs a Poly1305 check: PROTOCOL.md 5.7.2).
std::vector<Sample> make_garbage(int kind, std::size_t count, std::size_t hosts, std::mt19937& rng,
                                 const Victim& victim) {
  std::vector<Sample> out;
  for (std::size_t i = 0; i < count; ++i) {
    Sample s;
    s.from = "198.18." + std::to_string((i % hosts) / 250) + "." + std::to_string((i % hosts) % 250) + ":" +
             std::to_string(1024 + rng() % 60000);
    switch (kind) {
      case 0: {
        s.bytes.resize(1 + rng() % 1200);
        for (auto& b : s.bytes) b = static_cast<std::uint8_t>(rng());
        break;
      }
      case 1: s.bytes = with_header(1 + rng() % 0xfffffff0u, "[{\"t\":\"input\",\"ack\":0,\"f\":[]}]"); break;
      case 2: s.bytes = with_header(0, std::string(589, '[') + std::string(589, ']')); break;
      case 3: s.bytes = with_header(0, "[{\"t\":\"hello\",\"name\":\"x\",\"pad\":\"" + std::string(rng() % 400, '.')); break;
      case 4: {
        std::string p = "\x91\xdd\xff\xff\xff\xff";  // array32 of 2^32-1
        s.bytes = with_header(0, p);
        s.bytes[6] = 1;  // MessagePack
        break;
      }
      default: {
        s.from = victim.from;
        Header h;
        h.session = victim.session;
        h.sequence = static_cast<std::uint16_t>(100 + i % 30000);
        write_header(h, s.bytes);
        s.bytes.resize(kHeaderBytes + kSealTagBytes + 16 + rng() % 200);
        for (std::size_t b = kHeaderBytes; b < s.bytes.size(); ++b) s.bytes[b] = static_cast<std::uint8_t>(rng());
        break;
      }
    }
    out.push_back(std::move(s));
  }
  return out;
}

double rate_per_s(ServerEndpoint& server, const std::vector<Sample>& samples, int passes, std::uint64_t& now) {
  const auto start = std::chrono::steady_clock::now();
  std::size_t n = 0;
  for (int p = 0; p < passes; ++p) {
    for (const auto& s : samples) {
      server.receive(s.from, s.bytes, now);
      if (++n % 100 == 0) {
        ++now;  // 100 datagrams per millisecond of the server's clock
        server.update(now);
        server.take_datagrams();
      }
    }
  }
  const std::chrono::duration<double> secs = std::chrono::steady_clock::now() - start;
  return static_cast<double>(n) / secs.count();
}

}  // namespace

TEST_CASE("Garbage rejection rate", "[bench][garbage]") {
  const char* names[] = {"random bytes", "our header, unknown session", "589-deep JSON, hello sized",
                         "truncated JSON hello", "MessagePack claiming 2^32 elements",
                         "forged sealed datagram, live session (53-253 B)"};
  std::mt19937 rng(12);
  std::printf("| garbage | from | datagrams/s (one core) | counted as |\n|---|---|---|---|\n");
  for (int kind = 0; kind < 6; ++kind) {
    for (int variant = 0; variant < 3; ++variant) {
      // 1000 hosts within their rates, one host over them, 1000 hosts with no rate limits
      // (what the parser alone costs).
      const std::size_t hosts = variant == 1 ? 1 : 1000;
      ServerConfig config = test_server_config();
      if (variant == 2)
        config.address_datagrams_per_s = config.address_datagram_burst = config.hellos_per_s = config.hello_burst =
            1'000'000'000;
      Harness h(config);
      ServerEndpoint& server = h.server;
      Victim victim;
      if (kind == 5) {
        // One connected client: the forger has its address and session id.
        Peer& p = h.add_client(ClientConfig{});
        p.client.connect(h.now);
        REQUIRE(h.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
        p.client.send_input({}, h.now);
        victim = {p.address, read_header(p.client.take_datagrams().at(0))->session};
        if (variant == 1) victim.from = "198.18.0.0:5000";  // from another address: not opened
        h.server.take_events();
      }
      const auto samples = make_garbage(kind, 20000, hosts, rng, victim);
      std::uint64_t now = h.now + 1;
      const double rate = rate_per_s(server, samples, 10, now);
      std::string counted;
      for (std::size_t r = 0; r < kRejectCount; ++r)
        if (server.rejects().counts[r] > 0)
          counted += std::string(counted.empty() ? "" : ", ") + std::string(to_string(static_cast<Reject>(r))) + " " +
                     std::to_string(server.rejects().counts[r]);
      const char* from[] = {"1000 hosts", "1 host", "1000 hosts, no rate limits"};
      const char* victim_from[] = {"the session's host", "another host", "the session's host, no rate limits"};
      std::printf("| %s | %s | %.0f | %s |\n", names[kind], kind == 5 ? victim_from[variant] : from[variant], rate,
                  counted.c_str());
      CHECK(server.sessions().size() == (kind == 5 ? 1u : 0u));
      CHECK(server.take_inputs().empty());
    }
  }
}
