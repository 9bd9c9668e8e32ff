#include "app/stats.hpp"

#include <algorithm>

#include "fts/sim/percentile.hpp"

namespace fts::server {

Percentiles percentiles(std::vector<double>& v) {
  Percentiles p;
  p.samples = v.size();
  if (v.empty()) return p;
  p.p50_us = sim::percentile(v, 0.50);
  p.p99_us = sim::percentile(v, 0.99);
  p.max_us = *std::max_element(v.begin(), v.end());
  return p;
}

}  // namespace fts::server
