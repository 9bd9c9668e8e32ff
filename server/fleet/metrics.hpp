// Prometheus /metrics (prometheus-cpp's exposer, its own threads, on --metrics
// ADDR:PORT, never the game port). The tick loop hands over a sample once per tick;
// cumulative figures become counters (incremented by what is new since the last sample).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <prometheus/counter.h>
#include <prometheus/exposer.h>
#include <prometheus/gauge.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

#include "app/stats.hpp"
#include "fleet/fleet_names.hpp"
#include "fleet/fleet_state.hpp"
#include "fts/protocol/reject.hpp"

namespace fts::server {

struct MetricsSample {
  FleetState fleet;
  std::uint64_t ticks = 0, skipped_ticks = 0;
  Stats::Totals totals;
  protocol::RejectCounters drops;
  std::uint32_t sessions_connected = 0, sessions_away = 0;
  std::uint64_t journal_failing = 0, journal_failures = 0;  // rooms not journaling now; times one stopped
  std::uint64_t rooms_moved = 0, rooms_adopted = 0, handovers_refused = 0, rooms_forgotten = 0;  // rooms that move (issue 42)
  std::array<std::uint64_t, kFleetNameCount> agones_update_failures{};  // by row of kFleetNames
  // The profile writer (issue 41), when --profiles is on: writes the tick handed over not
  // yet taken, writes spooled for the database, whether the database answers.
  bool profiles = false;
  std::uint64_t profiles_queued = 0, profiles_pending = 0, profiles_results = 0, profiles_dropped = 0;
  bool profiles_db_up = false;
};

class Metrics {
 public:
  // Listens on "ADDR:PORT"; throws std::runtime_error naming the address when it cannot.
  explicit Metrics(const std::string& address);
  ~Metrics();
  Metrics(const Metrics&) = delete;
  Metrics& operator=(const Metrics&) = delete;

  void update(const MetricsSample& sample);
  void observe_tick(double seconds);
  // Journal fsync latency (issue 15's journal calls this when journaling).
  void observe_journal_sync(double seconds);

  static constexpr int kHttpThreads = 4;          // civetweb workers
  static constexpr int kRequestTimeoutMs = 3000;  // a request not received by then is dropped

 private:
  struct Cumulative;  // a counter and the value it was last brought to
  std::shared_ptr<prometheus::Registry> registry_;
  std::unique_ptr<prometheus::Exposer> exposer_;
  prometheus::Gauge* players_ = nullptr;
  prometheus::Gauge* rooms_ = nullptr;
  prometheus::Gauge* draining_ = nullptr;
  prometheus::Gauge* sessions_connected_ = nullptr;
  prometheus::Gauge* sessions_away_ = nullptr;
  prometheus::Gauge* journal_failing_ = nullptr;
  prometheus::Gauge* profiles_queued_ = nullptr;
  prometheus::Gauge* profiles_pending_ = nullptr;
  prometheus::Gauge* profiles_db_up_ = nullptr;
  prometheus::Histogram* tick_seconds_ = nullptr;
  prometheus::Histogram* journal_sync_seconds_ = nullptr;
  // One for each row of counter_table() (metrics.cpp), however many it has.
  std::vector<Cumulative> counters_;
};

}  // namespace fts::server
