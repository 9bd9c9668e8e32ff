// The one seeded random generator of a scene or match: xoshiro256** seeded by splitmix64.
// Hand-written on purpose: its state is four words we can hash and serialise, and the
// <random> distributions are not bit-identical across standard libraries.
#pragma once

#include <array>
#include <cstdint>

namespace fts::sim {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0);

  std::uint64_t next_u64();
  // Uniform integer in [lo, hi] (inclusive), unbiased (rejection).
  std::int64_t uniform_int(std::int64_t lo, std::int64_t hi);
  // Uniform double in [0, 1) with 53 random bits.
  double uniform01();
  // Uniform double in [lo, hi).
  double uniform(double lo, double hi);

  const std::array<std::uint64_t, 4>& state() const { return s_; }
  void set_state(const std::array<std::uint64_t, 4>& s) { s_ = s; }

 private:
  std::array<std::uint64_t, 4> s_{};
};

}  // namespace fts::sim
