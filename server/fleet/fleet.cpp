#include "fleet/fleet.hpp"

#include "app/game_host.hpp"
#include "app/log.hpp"
#include "fleet/fleet_state.hpp"

namespace fts::server {
namespace {

constexpr std::uint64_t kShutdownWaitMs = 5000;  // for an unreachable sidecar after a drain

}  // namespace

Fleet::Fleet(const Options& options) : options_(options), drain_(options.drain_grace_ms) {
  if (!options.metrics_address.empty()) metrics_ = std::make_unique<Metrics>(options.metrics_address);
  if (options.agones_port != 0) {
    AgonesClientConfig c;
    c.port = options.agones_port;
    agones_ = std::make_unique<AgonesClient>(c);
    wanted_.version = FTS_VERSION;
    wanted_.capacity = agones_capacity(options.max_rooms, options.max_players);
    if (options.max_rooms > wanted_.capacity.rooms)  // beyond Agones' List limit
      log_record(spdlog::level::warn, "agones_rooms_bounded",
                 {{"max_rooms", options.max_rooms}, {"published", wanted_.capacity.rooms},
                  {"note", "codes of rooms past the first ones (by id) are not in the rooms List until one closes"}});
  }
}

Fleet::~Fleet() = default;

void Fleet::bound() {
  if (!agones_) return;
  wanted_.ready = true;
  agones_->want(wanted_);
  log_record(spdlog::level::info, "agones",
             {{"port", options_.agones_port}, {"health_ms", options_.agones_health_ms},
              {"seats", wanted_.capacity.seats}, {"rooms", wanted_.capacity.rooms}});
}

void Fleet::tick(GameHost& host, std::uint64_t ticks, std::uint64_t skipped, std::uint64_t now_ms) {
  if (!metrics_ && !agones_ && !drain_.active()) return;  // nothing to do: no per-tick cost
  const FleetState state = observe(host);
  if (drain_.over(now_ms, state.rooms) && !over_logged_) {
    over_logged_ = true;
    log_record(spdlog::level::info, "drain_over", {{"timed_out", drain_.timed_out()}, {"rooms", state.rooms}});
  }
  if (metrics_) {
    MetricsSample s;
    s.fleet = state;
    s.ticks = ticks;
    s.skipped_ticks = skipped;
    s.totals = host.stats().totals;
    s.drops = host.endpoint().rejects();
    for (const auto& session : host.endpoint().sessions()) ++(session.connected ? s.sessions_connected : s.sessions_away);
    const auto journal = host.journal_health();
    s.journal_failing = journal.failing;
    s.journal_failures = journal.failures;
    s.rooms_moved = host.rooms_moved();
    s.rooms_adopted = host.rooms_adopted();
    s.handovers_refused = host.handovers_refused();
    s.rooms_forgotten = host.rooms_forgotten();
    if (const auto* w = host.profiles()) {
      const auto ps = w->stats();
      s.profiles = true;
      s.profiles_queued = ps.queued;
      s.profiles_pending = ps.pending;
      s.profiles_results = ps.results;
      s.profiles_dropped = ps.dropped;
      s.profiles_db_up = ps.connected;
    }
    if (agones_)
      for (std::size_t i = 0; i < kFleetNameCount; ++i) s.agones_update_failures[i] = agones_->update_failures(i);
    metrics_->update(s);
  }
  if (agones_) {
    bool changed = !(state == wanted_.state);
    wanted_.state = state;
    // Health comes from here, the tick loop: a stuck loop stops it and Agones replaces
    // the server.
    if (now_ms >= next_health_ms_) {
      ++wanted_.health_seq;
      next_health_ms_ = now_ms + options_.agones_health_ms;
      changed = true;
    }
    if (drain_.over_ms() && !wanted_.shutdown) {
      wanted_.shutdown = true;
      changed = true;
    }
    if (changed) agones_->want(wanted_);
  }
}

void Fleet::observe_tick(double seconds) {
  if (metrics_) metrics_->observe_tick(seconds);
}

void Fleet::drain(GameHost& host, std::uint64_t now_ms) {
  if (drain_.active()) return;
  drain_.start(now_ms);
  host.set_draining(true);
  log_record(spdlog::level::info, "drain", {{"grace_ms", options_.drain_grace_ms}});
}

bool Fleet::finished(std::uint64_t now_ms) const {
  const auto over = drain_.over_ms();
  if (!over) return false;
  if (!agones_) return true;
  return agones_->shutdown_sent() || now_ms - *over >= kShutdownWaitMs;
}

}  // namespace fts::server
