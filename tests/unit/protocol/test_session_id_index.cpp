// SessionIdIndex: the session table's hash table by session id (session_id_index.hpp).
#include <catch2/catch.hpp>

#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "fts/protocol/session_id_index.hpp"

using fts::protocol::SessionIdIndex;

TEST_CASE("SessionIdIndex: sets, finds and erases as a std::map of the same operations does",
          "[protocol][sessions]") {
  // A seeded walk over few keys, so runs of probing wrap and erasures move entries back;
  // after each step every key of the range is looked up in both.
  std::vector<int> values(64);
  for (const std::uint32_t span : {24u, 600u}) {
    SessionIdIndex<int> index;
    std::map<std::uint32_t, int*> ref;
    std::mt19937 rng(39);
    for (int step = 0; step < 4000; ++step) {
      const auto id = static_cast<std::uint32_t>(rng() % span) * (span > 100 ? 7919u : 1u);
      if (rng() % 3 == 0) {
        REQUIRE(index.erase(id) == (ref.erase(id) == 1));
      } else {
        int* v = &values[rng() % values.size()];
        index.set(id, v);
        ref[id] = v;
      }
      REQUIRE(index.size() == ref.size());
      for (std::uint32_t k = 0; k < span; ++k) {
        const std::uint32_t key = k * (span > 100 ? 7919u : 1u);
        const auto it = ref.find(key);
        REQUIRE(index.find(key) == (it == ref.end() ? nullptr : it->second));
      }
    }
  }
}

TEST_CASE("SessionIdIndex: empty, then grown past its first size, finds every id", "[protocol][sessions]") {
  SessionIdIndex<int> index;
  CHECK(index.find(0) == nullptr);
  CHECK_FALSE(index.erase(5));
  std::vector<int> values(1000);
  for (std::uint32_t i = 0; i < 1000; ++i) index.set(0x9E370000u + i * 4099u, &values[i]);
  CHECK(index.size() == 1000);
  for (std::uint32_t i = 0; i < 1000; ++i) REQUIRE(index.find(0x9E370000u + i * 4099u) == &values[i]);
  CHECK(index.find(1) == nullptr);
}
