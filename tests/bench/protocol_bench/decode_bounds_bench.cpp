// Cheap rejection (issue 12): how long a payload nested past the bound takes to refuse.
// A benchmark: reported, never asserted on time. Run: fts-protocol-bench "[bounds]".
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>

#include "fts/protocol/codec.hpp"
#include "raw_datagrams.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

TEST_CASE("Decode bounds: deep nesting is cheap to refuse", "[bench][bounds]") {
  const auto deep = raw_datagram(nested_json(589), Encoding::json);  // 1199 bytes
  const auto start = std::chrono::steady_clock::now();
  constexpr int kRuns = 20000;
  for (int i = 0; i < kRuns; ++i) CHECK_FALSE(decode_datagram(deep).ok());
  const std::chrono::duration<double, std::micro> us = std::chrono::steady_clock::now() - start;
  std::printf("589-deep JSON (1199 bytes) refused in %.2f us each\n", us.count() / kRuns);
}
