// 64-bit FNV-1a over the exact bits of values: the state hash of determinism tests.
#pragma once

#include <bit>
#include <cstdint>
#include <string_view>

namespace fts::sim {

class Hasher {
 public:
  void add_u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      h_ ^= (v >> (8 * i)) & 0xffu;
      h_ *= 0x100000001b3ull;
    }
  }
  void add_i64(std::int64_t v) { add_u64(static_cast<std::uint64_t>(v)); }
  void add_double(double v) { add_u64(std::bit_cast<std::uint64_t>(v)); }
  void add_string(std::string_view s) {
    add_u64(s.size());
    for (unsigned char c : s) {
      h_ ^= c;
      h_ *= 0x100000001b3ull;
    }
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace fts::sim
