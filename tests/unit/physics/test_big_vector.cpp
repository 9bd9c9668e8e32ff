#include <catch2/catch.hpp>

#include <cstdint>

#include "fts/sim/big_vector.hpp"
#include "fts/sim/step_buffers.hpp"

using namespace fts::sim;

TEST_CASE("Big vectors: large ones start on a huge page, small ones are plain, both hold their values", "[physics]") {
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  BigVector<std::uint32_t> small(1000);
  BigVector<std::uint32_t> large;
  for (std::uint32_t i = 0; i < 600'000; ++i) {  // grows through the threshold (2.4 MB)
    large.push_back(i * 7u);
    if (i < small.size()) small[i] = i;
  }
  CHECK(reinterpret_cast<std::uintptr_t>(large.data()) % kHugePage == 0);
  CHECK(large.capacity() * sizeof(std::uint32_t) >= detail::kBigBytes);
  CHECK(small.capacity() * sizeof(std::uint32_t) < detail::kBigBytes);
  bool same = true;
  for (std::uint32_t i = 0; i < large.size(); ++i) same = same && large[i] == i * 7u;
  CHECK(same);
  CHECK(small[999] == 999u);
  // Over-aligned elements keep their alignment below the threshold too.
  BigVector<detail::SolverBall> bodies(3);
  CHECK(reinterpret_cast<std::uintptr_t>(bodies.data()) % alignof(detail::SolverBall) == 0);
  large.clear();
  large.shrink_to_fit();  // frees through the same path it came from (ASan checks the pair)
  CHECK(large.capacity() == 0);
}
