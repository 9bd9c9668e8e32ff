#include "fleet/metrics.hpp"

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <prometheus/counter.h>
#include <prometheus/exposer.h>
#include <prometheus/gauge.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

namespace fts::server {

struct Metrics::Cumulative {
  prometheus::Counter* counter = nullptr;
  std::function<std::uint64_t(const MetricsSample&)> value;
  std::uint64_t seen = 0;
};

namespace {

// One row per counter: name, help, labels, where its value comes from.
struct CounterRow {
  const char* name;
  const char* help;
  prometheus::Labels labels;
  std::function<std::uint64_t(const MetricsSample&)> value;
};

std::vector<CounterRow> counter_table() {
  using S = const MetricsSample&;
  std::vector<CounterRow> rows = {
      {"fts_ticks_total", "Simulation ticks run", {}, [](S s) { return s.ticks; }},
      {"fts_skipped_ticks_total", "Ticks skipped because the loop fell behind", {}, [](S s) { return s.skipped_ticks; }},
      {"fts_datagrams_total", "UDP datagrams", {{"direction", "in"}}, [](S s) { return s.totals.datagrams_in; }},
      {"fts_datagrams_total", "UDP datagrams", {{"direction", "out"}}, [](S s) { return s.totals.datagrams_out; }},
      {"fts_bytes_total", "UDP payload bytes", {{"direction", "in"}}, [](S s) { return s.totals.bytes_in; }},
      {"fts_bytes_total", "UDP payload bytes", {{"direction", "out"}}, [](S s) { return s.totals.bytes_out; }},
      {"fts_purchases_total", "Shop purchases by result", {{"result", "ok"}}, [](S s) { return s.totals.purchases; }},
      {"fts_purchases_total", "Shop purchases by result", {{"result", "refused"}},
       [](S s) { return s.totals.purchases_refused; }},
      {"fts_journal_failures_total", "Times a room's journal stopped on an I/O error (disk full, read-only)", {},
       [](S s) { return s.journal_failures; }},
      {"fts_handovers_total", "Rooms handed over to a peer, taken from one, kept (the peer refused), or taken and forgotten (never confirmed)",
       {{"result", "moved"}}, [](S s) { return s.rooms_moved; }},
      {"fts_handovers_total", "Rooms handed over to a peer, taken from one, kept (the peer refused), or taken and forgotten (never confirmed)",
       {{"result", "adopted"}}, [](S s) { return s.rooms_adopted; }},
      {"fts_handovers_total", "Rooms handed over to a peer, taken from one, kept (the peer refused), or taken and forgotten (never confirmed)",
       {{"result", "refused"}}, [](S s) { return s.handovers_refused; }},
      {"fts_handovers_total", "Rooms handed over to a peer, taken from one, kept (the peer refused), or taken and forgotten (never confirmed)",
       {{"result", "forgotten"}}, [](S s) { return s.rooms_forgotten; }},
      {"fts_profiles_results_total", "Match results written to the profile database (new ones; a repeat counts 0)", {},
       [](S s) { return s.profiles_results; }},
      {"fts_profiles_dropped_total", "Profile writes dropped: the writer's queue was full (each logged)", {},
       [](S s) { return s.profiles_dropped; }},
  };
  for (std::size_t i = 0; i < kFleetNames.size(); ++i)
    rows.push_back({"fts_agones_update_failures_total",
                    "Counter and List updates the Agones sidecar did not take (each retried with backoff; Ready "
                    "and Health do not wait for them)",
                    {{"kind", to_string(kFleetNames[i].kind)}, {"name", kFleetNames[i].name}},
                    [i](S s) { return s.agones_update_failures[i]; }});
  for (std::size_t i = 0; i < protocol::kRejectCount; ++i) {
    const auto r = static_cast<protocol::Reject>(i);
    rows.push_back({"fts_drops_total", "Datagrams or messages dropped, by reason", {{"reason", std::string(protocol::to_string(r))}},
                    [r](S s) { return s.drops[r]; }});
  }
  return rows;
}

prometheus::Gauge* gauge(prometheus::Registry& reg, const char* name, const char* help,
                         const prometheus::Labels& labels = {}) {
  return &prometheus::BuildGauge().Name(name).Help(help).Register(reg).Add(labels);
}

}  // namespace

Metrics::Metrics(const std::string& address) : registry_(std::make_shared<prometheus::Registry>()) {
  try {
    // civetweb's options (prometheus-cpp passes them through). A scrape is one small GET:
    // a client that has not sent its request within 3 s is cut off (a slowloris holds a
    // worker for at most that long), a request's head may be 8 KiB, and four workers
    // serve while one is held. Keep-alive is off: a worker is never held by an idle
    // connection between scrapes. The tick loop never waits for any of it.
    exposer_ = std::make_unique<prometheus::Exposer>(std::vector<std::string>{
        "listening_ports", address, "num_threads", std::to_string(kHttpThreads), "request_timeout_ms",
        std::to_string(kRequestTimeoutMs), "max_request_size", "8192", "enable_keep_alive", "no"});
  } catch (const std::exception& e) {
    throw std::runtime_error("--metrics: cannot listen on " + address + ": " + e.what());
  }
  auto& reg = *registry_;
  players_ = gauge(reg, "fts_players", "Connected players");
  rooms_ = gauge(reg, "fts_rooms", "Live rooms (matches with a connected player)");
  draining_ = gauge(reg, "fts_draining", "1 while draining (no new players or rooms)");
  sessions_connected_ = gauge(reg, "fts_sessions", "Sessions by state", {{"state", "connected"}});
  sessions_away_ = gauge(reg, "fts_sessions", "Sessions by state", {{"state", "away"}});
  journal_failing_ = gauge(reg, "fts_journal_failing_rooms", "Rooms whose journal is not writing (an I/O error; retried every second)");
  profiles_queued_ = gauge(reg, "fts_profiles_queue", "Profile writes handed over by the tick, not yet taken by the writer");
  profiles_pending_ = gauge(reg, "fts_profiles_spool",
                            "Profile writes in the durable spool, waiting for the database (it is down or slow)");
  profiles_db_up_ = gauge(reg, "fts_profiles_db_up", "1 while the profile database answers (-1: profiles are off)");
  // 0.1 ms .. 100 ms: a 100 Hz tick has 10 ms.
  tick_seconds_ = &prometheus::BuildHistogram()
                       .Name("fts_tick_duration_seconds")
                       .Help("Time to run one tick (step, results, snapshots)")
                       .Register(reg)
                       .Add({}, prometheus::Histogram::BucketBoundaries{0.0001, 0.00025, 0.0005, 0.001, 0.0025, 0.005,
                                                                         0.01, 0.025, 0.05, 0.1});
  const auto rows = counter_table();
  counters_.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    auto& family = prometheus::BuildCounter().Name(rows[i].name).Help(rows[i].help).Register(reg);
    counters_[i].counter = &family.Add(rows[i].labels);
    counters_[i].value = rows[i].value;
  }
  exposer_->RegisterCollectable(registry_);
}

Metrics::~Metrics() = default;

void Metrics::update(const MetricsSample& s) {
  players_->Set(static_cast<double>(s.fleet.players.size()));
  rooms_->Set(s.fleet.rooms);
  draining_->Set(s.fleet.draining ? 1 : 0);
  sessions_connected_->Set(s.sessions_connected);
  sessions_away_->Set(s.sessions_away);
  journal_failing_->Set(static_cast<double>(s.journal_failing));
  profiles_queued_->Set(static_cast<double>(s.profiles_queued));
  profiles_pending_->Set(static_cast<double>(s.profiles_pending));
  profiles_db_up_->Set(s.profiles ? (s.profiles_db_up ? 1 : 0) : -1);
  for (auto& c : counters_) {
    const std::uint64_t v = c.value(s);
    if (v > c.seen) c.counter->Increment(static_cast<double>(v - c.seen));
    c.seen = v;
  }
}

void Metrics::observe_tick(double seconds) { tick_seconds_->Observe(seconds); }

void Metrics::observe_journal_sync(double seconds) {
  if (!journal_sync_seconds_)
    journal_sync_seconds_ = &prometheus::BuildHistogram()
                                 .Name("fts_journal_sync_seconds")
                                 .Help("Latency of the journal's sync to disk")
                                 .Register(*registry_)
                                 .Add({}, prometheus::Histogram::BucketBoundaries{0.0001, 0.001, 0.005, 0.01, 0.05,
                                                                                   0.1, 0.5});
  journal_sync_seconds_->Observe(seconds);
}

}  // namespace fts::server
