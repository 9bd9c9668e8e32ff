// Two doubles in one 16-byte register (GCC and Clang vector extensions): a vector's x
// and y, or a box's low or high corner, tested together (internal to fts_common). The
// operations are the scalar IEEE ones lane by lane, so the results are those of the
// scalar code, bit for bit.
#pragma once

#include <cstdint>
#include <cstring>

#include "fts/sim/vec2.hpp"

namespace fts::sim::detail {

using D2 = double __attribute__((vector_size(16)));
using Bits2 = std::uint64_t __attribute__((vector_size(16)));

// The two doubles from p on, as numbers.
inline D2 lanes(const double* p) {
  D2 r;
  std::memcpy(&r, p, sizeof r);
  return r;
}
inline D2 lanes(const Vec2& v) { return lanes(&v.x); }
// A vector's two doubles as bits.
inline Bits2 bits2(const Vec2& v) {
  Bits2 r;
  std::memcpy(&r, &v.x, sizeof r);
  return r;
}

}  // namespace fts::sim::detail
