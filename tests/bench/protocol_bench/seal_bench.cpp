// Cost of sealing and opening one datagram (issue 12, PROTOCOL.md 5.7), one core. A
// benchmark: figures are printed for BENCHMARKS.md, never asserted on time. Run:
// fts-protocol-bench "[seal]".
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>

#include "fts/protocol/seal.hpp"

using namespace fts::protocol;

namespace {

double ns_per(std::size_t n, std::chrono::steady_clock::time_point start) {
  const std::chrono::duration<double, std::nano> d = std::chrono::steady_clock::now() - start;
  return d.count() / static_cast<double>(n);
}

}  // namespace

TEST_CASE("Seal and open cost per datagram", "[bench][seal]") {
  SessionKeys k;
  for (std::size_t i = 0; i < k.rx.size(); ++i) k.rx[i] = static_cast<std::uint8_t>(i), k.tx[i] = static_cast<std::uint8_t>(~i);
  std::printf("| payload | seal (ns) | open (ns) | open, forged tag (ns) |\n|---|---|---|---|\n");
  for (std::size_t size : {std::size_t{40}, std::size_t{250}, std::size_t{600}, kMaxDatagramBytes - kHeaderBytes - kSealTagBytes}) {
    const std::vector<std::uint8_t> payload(size, 0x5a);
    // Sealing: into one reused buffer. Opening: a ring of 4096 datagrams with distinct
    // sequences, opened by a fresh channel (a fresh replay window) on every pass.
    constexpr std::size_t kRing = 4096, kPasses = 50, kN = kRing * kPasses;
    const SessionKeys peer{k.tx, k.rx};
    SealedChannel tx(k, SealDirection::server_to_client, SealDirection::client_to_server);
    Header h;
    h.session = 9;
    std::vector<std::uint8_t> out;
    out.reserve(kMaxDatagramBytes);
    auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < kN; ++i) {
      h.sequence = static_cast<std::uint16_t>(i % 65535 + 1);
      out.clear();
      tx.seal(h, payload, out);
    }
    const double seal_ns = ns_per(kN, t0);
    std::vector<std::vector<std::uint8_t>> ring(kRing);
    SealedChannel ring_tx(k, SealDirection::server_to_client, SealDirection::client_to_server);
    for (std::size_t i = 0; i < kRing; ++i) {
      h.sequence = static_cast<std::uint16_t>(i + 1);
      ring_tx.seal(h, payload, ring[i]);
    }
    auto open_all = [&](Reject* expect) {
      std::vector<std::uint8_t> plain;
      plain.reserve(kMaxDatagramBytes);
      std::size_t as_expected = 0;
      const auto start = std::chrono::steady_clock::now();
      for (std::size_t pass = 0; pass < kPasses; ++pass) {
        SealedChannel rx(peer, SealDirection::client_to_server, SealDirection::server_to_client);
        for (const auto& d : ring) {
          const auto why = rx.open(*read_header(d), d, plain);
          as_expected += expect ? (why == *expect) : !why;
        }
      }
      CHECK(as_expected == kN);
      return ns_per(kN, start);
    };
    const double open_ns = open_all(nullptr);
    for (auto& d : ring) d.back() ^= 1;
    Reject forged = Reject::forged;
    const double forged_ns = open_all(&forged);
    std::printf("| %zu B | %.0f | %.0f | %.0f |\n", size, seal_ns, open_ns, forged_ns);
  }
}
