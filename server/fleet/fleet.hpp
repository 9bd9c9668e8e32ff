// The server's side of a fleet, fed by the tick loop once per tick (net/udp_server.cpp):
// Prometheus /metrics, the Agones SDK client (Ready, Health, Counters/Lists, labels,
// Shutdown) and the drain. Everything that may block runs on other threads.
#pragma once

#include <cstdint>
#include <memory>

#include "app/options.hpp"
#include "fleet/agones_client.hpp"
#include "fleet/drain.hpp"
#include "fleet/metrics.hpp"

namespace fts::server {

class GameHost;

class Fleet {
 public:
  // Starts what the options ask for; throws std::runtime_error when /metrics cannot listen.
  explicit Fleet(const Options& options);
  ~Fleet();

  bool agones() const { return agones_ != nullptr; }
  // The game port is bound: Agones Ready.
  void bound();
  // Once per tick, after the tick ran (ticks: run so far; skipped: skipped so far).
  void tick(GameHost& host, std::uint64_t ticks, std::uint64_t skipped, std::uint64_t now_ms);
  void observe_tick(double seconds);
  // Stop taking players and rooms; Shutdown once the last room ends or the grace runs out.
  void drain(GameHost& host, std::uint64_t now_ms);
  bool draining() const { return drain_.active(); }
  // The drain is over and Agones took the Shutdown (or did not answer within 5 s).
  bool finished(std::uint64_t now_ms) const;
  Metrics* metrics() { return metrics_.get(); }

 private:
  Options options_;
  std::unique_ptr<Metrics> metrics_;
  std::unique_ptr<AgonesClient> agones_;
  AgonesWanted wanted_;
  std::uint64_t next_health_ms_ = 0;
  Drain drain_;
  bool over_logged_ = false;
};

}  // namespace fts::server
