// Garbage rejection rate of ServerEndpoint::receive (issue 12), one core. A benchmark:
// figures are printed for BENCHMARKS.md, never asserted on time. Hidden from the default
// run: fts_protocol_tests "[.bench][garbage]".
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

// kind: 0 random bytes, 1 our header + random session + junk, 2 deep nesting (hello
// sized), 3 session 0 + truncated JSON, 4 MessagePack that lies about its sizes.
std::vector<Sample> make_garbage(int kind, std::size_t count, std::size_t hosts, std::mt19937& rng) {
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
      default: {
        std::string p = "\x91\xdd\xff\xff\xff\xff";  // array32 of 2^32-1
        s.bytes = with_header(0, p);
        s.bytes[6] = 1;  // MessagePack
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

TEST_CASE("Garbage rejection rate", "[.bench][garbage]") {
  const char* names[] = {"random bytes", "our header, unknown session", "589-deep JSON, hello sized",
                         "truncated JSON hello", "MessagePack claiming 2^32 elements"};
  std::mt19937 rng(12);
  std::printf("| garbage | from | datagrams/s (one core) | counted as |\n|---|---|---|---|\n");
  for (int kind = 0; kind < 5; ++kind) {
    for (int variant = 0; variant < 3; ++variant) {
      // 1000 hosts within their rates, one host over them, 1000 hosts with no rate limits
      // (what the parser alone costs).
      const std::size_t hosts = variant == 1 ? 1 : 1000;
      ServerConfig config = test_server_config();
      if (variant == 2)
        config.address_datagrams_per_s = config.address_datagram_burst = config.hellos_per_s = config.hello_burst =
            1'000'000'000;
      ServerEndpoint server(config);
      const auto samples = make_garbage(kind, 20000, hosts, rng);
      std::uint64_t now = 1000;
      const double rate = rate_per_s(server, samples, 10, now);
      std::string counted;
      for (std::size_t r = 0; r < kRejectCount; ++r)
        if (server.rejects().counts[r] > 0)
          counted += std::string(counted.empty() ? "" : ", ") + std::string(to_string(static_cast<Reject>(r))) + " " +
                     std::to_string(server.rejects().counts[r]);
      const char* from[] = {"1000 hosts", "1 host", "1000 hosts, no rate limits"};
      std::printf("| %s | %s | %.0f | %s |\n", names[kind], from[variant], rate, counted.c_str());
      CHECK(server.sessions().empty());
    }
  }
}
