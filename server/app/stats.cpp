#include "app/stats.hpp"

#include <algorithm>

namespace fts::server {

Percentiles percentiles(std::vector<double>& v) {
  Percentiles p;
  p.samples = v.size();
  if (v.empty()) return p;
  auto at = [&](double q) {
    const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
  };
  p.p50_us = at(0.50);
  p.p99_us = at(0.99);
  p.max_us = *std::max_element(v.begin(), v.end());
  return p;
}

}  // namespace fts::server
