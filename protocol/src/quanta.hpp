// The one quantizer of the wire (internal): positions, velocities, radii and masses in
// 1/16 units (PROTOCOL.md 8.1). quantize() and the snapshot delta both use it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "fts/protocol/constants.hpp"

namespace fts::protocol::wire {

// v in quanta, rounded half away from zero, within +-lim (not finite: 0).
inline std::int64_t to_quanta(double v, std::int64_t lim = kMaxQuantized) {
  if (!std::isfinite(v)) return 0;
  const double l = static_cast<double>(lim);
  return static_cast<std::int64_t>(std::clamp(std::round(v * kQuantaPerUnit), -l, l));
}
inline double from_quanta(std::int64_t q) { return static_cast<double>(q) / kQuantaPerUnit; }

// A value a client rebuilt by adding hostile deltas may pass kMaxQuantized: it is read
// back within this wider bound, still far from int64's limits.
inline constexpr std::int64_t kMaxRebuiltQuanta = std::int64_t{1} << 50;

}  // namespace fts::protocol::wire
