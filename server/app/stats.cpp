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

Stats::Totals Stats::Totals::operator-(const Totals& e) const {
  return {datagrams_in - e.datagrams_in, datagrams_out - e.datagrams_out, bytes_in - e.bytes_in,
          bytes_out - e.bytes_out,       purchases - e.purchases,         purchases_refused - e.purchases_refused};
}

}  // namespace fts::server
