// The one percentile rule for reported figures (tick times, round trips).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>

namespace fts::sim {

// The q-quantile (0..1) of the samples by nearest rank, 0 for none; reorders them.
inline double percentile(std::span<double> samples, double q) {
  if (samples.empty()) return 0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(samples.size() - 1) + 0.5);
  std::nth_element(samples.begin(), samples.begin() + static_cast<std::ptrdiff_t>(k), samples.end());
  return samples[k];
}

}  // namespace fts::sim
