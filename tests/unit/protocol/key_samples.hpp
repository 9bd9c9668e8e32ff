// Fixed key material for the sealing and identity tests: a 32-byte seed counting up from
// a first byte, and bytes as lower-case hex (the wire's spelling).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "fts/protocol/cookie.hpp"

namespace fts::protocol::test {

inline std::array<std::uint8_t, 32> seed_from(std::uint8_t first) {
  std::array<std::uint8_t, 32> s{};
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = static_cast<std::uint8_t>(first + i);
  return s;
}

inline std::string hex(std::span<const std::uint8_t> b) { return to_hex(b.data(), b.size()); }

}  // namespace fts::protocol::test
