// Counters and tick-time percentiles for the periodic stats line.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace fts::server {

struct Percentiles {
  double p50_us = 0, p99_us = 0, max_us = 0;
  std::size_t samples = 0;
};

// p50/p99/max of samples (microseconds); reorders the vector.
Percentiles percentiles(std::vector<double>& samples_us);

struct Stats {
  std::uint64_t datagrams_in = 0, datagrams_out = 0, bytes_in = 0, bytes_out = 0;
  std::uint64_t skipped_ticks = 0;
  std::map<std::string, std::uint64_t> drops;  // by reason, ordered for stable output
  std::vector<double> tick_us;
  // Since the start, never reset: the counters /metrics reports (server/fleet/metrics).
  struct Totals {
    std::uint64_t datagrams_in = 0, datagrams_out = 0, bytes_in = 0, bytes_out = 0;
    std::uint64_t purchases = 0, purchases_refused = 0;
  } totals;
  void reset_interval() {
    datagrams_in = datagrams_out = bytes_in = bytes_out = 0;
    drops.clear();
    tick_us.clear();
  }
};

}  // namespace fts::server
