// Counters and tick-time percentiles for the periodic stats line and /metrics.
#pragma once

#include <cstdint>
#include <vector>

namespace fts::server {

struct Percentiles {
  double p50_us = 0, p99_us = 0, max_us = 0;
  std::size_t samples = 0;
};

// p50/p99/max of samples (microseconds); reorders the vector.
Percentiles percentiles(std::vector<double>& samples_us);

struct Stats {
  // Since the start, never reset, and the only place they are counted: /metrics
  // (server/fleet/metrics) reports them, the stats line their change since its last line.
  struct Totals {
    std::uint64_t datagrams_in = 0, datagrams_out = 0, bytes_in = 0, bytes_out = 0;
    std::uint64_t purchases = 0, purchases_refused = 0;
    Totals operator-(const Totals& earlier) const;
  } totals;
  std::uint64_t skipped_ticks = 0;
  std::vector<double> tick_us;  // this interval's tick times

  void received(std::size_t bytes) {
    ++totals.datagrams_in;
    totals.bytes_in += bytes;
  }
  void sent(std::size_t bytes) {
    ++totals.datagrams_out;
    totals.bytes_out += bytes;
  }
  // The totals' change since the last reset_interval().
  Totals interval() const { return totals - interval_start_; }
  void reset_interval() {
    interval_start_ = totals;
    tick_us.clear();
  }

 private:
  Totals interval_start_;
};

}  // namespace fts::server
