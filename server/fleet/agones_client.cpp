#include "fleet/agones_client.hpp"

#include <algorithm>
#include <chrono>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "app/log.hpp"
#include "fts/room/json_fields.hpp"

namespace fts::server {
namespace {

using Clock = std::chrono::steady_clock;

struct Outcome {
  bool done = false;       // 2xx, or a 4xx that a retry cannot fix
  int status = 0;          // 0: no answer (refused, timed out)
  std::string error;
};

const char* op_name(SdkOp op) {
  switch (op) {
    case SdkOp::counter_capacity: return "counter_capacity";
    case SdkOp::list_capacity: return "list_capacity";
    case SdkOp::ready: return "ready";
    case SdkOp::health: return "health";
    case SdkOp::label: return "label";
    case SdkOp::counter: return "counter";
    case SdkOp::list_remove: return "list_remove";
    case SdkOp::list_add: return "list_add";
    case SdkOp::shutdown: return "shutdown";
  }
  return "?";
}

// One request; the answer's body is kept up to AgonesClient::kMaxBodyBytes, a longer
// one ends the call (error Canceled).
httplib::Result request(httplib::Client& http, const std::string& method, const std::string& path,
                        const std::string& body) {
  httplib::Request req;
  req.method = method;
  req.path = path;
  if (method != "GET") {
    req.body = body;
    req.set_header("Content-Type", "application/json");
  }
  auto answer = std::make_shared<std::string>();
  req.content_receiver = [answer](const char* data, std::size_t n, std::uint64_t, std::uint64_t) {
    if (answer->size() + n > AgonesClient::kMaxBodyBytes) return false;
    answer->append(data, n);
    return true;
  };
  httplib::Result r = http.send(req);
  if (r) r.value().body = std::move(*answer);
  return r;
}

Outcome send(httplib::Client& http, const SdkCall& c) {
  const httplib::Result r = request(http, c.method, c.path, c.body);
  Outcome o;
  if (!r) {
    o.error = httplib::to_string(r.error());
    return o;
  }
  o.status = r->status;
  o.done = r->status >= 200 && r->status < 500;
  if (r->status >= 300) o.error = r->body.substr(0, 200);
  return o;
}

}  // namespace

AgonesClient::AgonesClient(AgonesClientConfig config)
    : config_(std::move(config)),
      sync_(config_.update_retry_min_ms, config_.update_retry_max_ms),
      thread_([this] { run(); }), watchdog_([this] { watch(); }) {}

AgonesClient::~AgonesClient() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_cv_.notify_all();
  {
    std::lock_guard lock(watch_mutex_);
    abort_ = true;  // a call in flight is cut off now
  }
  watch_cv_.notify_all();
  thread_.join();
  {
    std::lock_guard lock(watch_mutex_);
    watch_stop_ = true;
  }
  watch_cv_.notify_all();
  watchdog_.join();
}

// Called with mutex_ held to register (after stop_ was checked: the destructor then
// aborts it), without to clear.
void AgonesClient::in_flight(httplib::Client* http) {
  {
    std::lock_guard lock(watch_mutex_);
    in_flight_ = http;
    deadline_ = Clock::now() + std::chrono::milliseconds(config_.timeout_ms);
  }
  if (http) watch_cv_.notify_all();
}

// httplib's timeouts bound each read and write, not a call: a sidecar that sends a byte
// of its answer now and then never trips them. Past its deadline (or when stopping) a
// call's socket is shut down, which Client::stop() may do from another thread; again
// every 50 ms until the call has ended (a shutdown before its socket opened misses it).
void AgonesClient::watch() {
  std::unique_lock lock(watch_mutex_);
  while (!watch_stop_) {
    if (in_flight_ && (abort_ || Clock::now() >= deadline_)) {
      in_flight_->stop();
      watch_cv_.wait_for(lock, std::chrono::milliseconds(50));
    } else if (in_flight_) {
      watch_cv_.wait_until(lock, deadline_);
    } else {
      watch_cv_.wait(lock);
    }
  }
}

void AgonesClient::want(const AgonesWanted& wanted) {
  {
    std::lock_guard lock(mutex_);
    wanted_ = wanted;
    changed_ = true;
  }
  changed_cv_.notify_one();
}

std::string AgonesClient::gameserver_state() const {
  std::lock_guard lock(mutex_);
  return gs_state_;
}

void AgonesClient::run() {
  const auto ms = [](std::uint32_t v) { return std::chrono::milliseconds(v); };
  httplib::Client http(config_.host, config_.port);
  const auto t = static_cast<time_t>(config_.timeout_ms / 1000);
  const auto t_us = static_cast<time_t>((config_.timeout_ms % 1000) * 1000);
  http.set_connection_timeout(t, t_us);
  http.set_read_timeout(t, t_us);
  http.set_write_timeout(t, t_us);

  std::uint32_t backoff_ms = config_.retry_min_ms;
  std::uint64_t spell = 0;  // failures of the sidecar in a row (see sidecar_failed)
  Clock::time_point spell_start;
  const Clock::time_point start = Clock::now();
  const auto now_ms = [start] {
    return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start).count());
  };
  auto next_poll = Clock::now();
  std::unique_lock lock(mutex_);
  while (!stop_) {
    const AgonesWanted wanted = wanted_;
    if (const auto call = sync_.next(wanted, now_ms())) {
      in_flight(&http);
      lock.unlock();
      const Outcome o = send(http, *call);
      in_flight(nullptr);
      if (o.done) {
        if (spell > 0) {
          const auto after = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - spell_start);
          log_record(spdlog::level::info, "agones_recovered",
                     {{"call", op_name(call->op)}, {"failures", spell}, {"after_ms", after.count()}});
          spell = 0;
        }
        if (call->row && sync_.retry(*call->row).failing()) {
          const auto& r = sync_.retry(*call->row);
          const auto& row = kFleetNames[*call->row];
          log_record(spdlog::level::info, "agones_update_recovered",
                     {{"kind", to_string(row.kind)}, {"name", row.name}, {"call", op_name(call->op)},
                      {"failures", r.spell()}, {"after_ms", now_ms() - r.spell_start_ms()}});
        }
        if (o.status >= 300)  // a 4xx: the sidecar will not take it, retrying cannot help
          log_record(spdlog::level::warn, "agones_refused",
                     {{"call", op_name(call->op)}, {"status", o.status}, {"error", o.error}});
        else
          log_record(spdlog::level::debug, "agones_call", {{"call", op_name(call->op)}, {"path", call->path}});
        sync_.done(*call);
        ready_sent_ = sync_.ready_sent();
        shutdown_sent_ = sync_.shutdown_sent();
        backoff_ms = config_.retry_min_ms;
        lock.lock();
        continue;
      }
      // Not answered, or a 5xx. A spell of failures of the sidecar (no answer at all, or a
      // failing Ready, Health, label or Shutdown) is logged at its first and every 20th (at
      // most one line per 40 s at the 2 s backoff), its end as agones_recovered.
      const auto sidecar_failed = [&] {
        const auto n = ++failures_;
        if (spell++ == 0) spell_start = Clock::now();
        if (spell == 1 || spell % 20 == 0)
          log_record(spdlog::level::warn, "agones_retry",
                     {{"call", op_name(call->op)}, {"status", o.status}, {"error", o.error}, {"failures", spell},
                      {"failures_total", n}, {"retry_ms", backoff_ms}});
      };
      if (call->row) {
        // A Counter or List the sidecar does not take (Agones answers 500 for one the
        // GameServer does not declare) waits its own backoff while every other call goes
        // on; logged at the first failure of its spell, its end as agones_update_recovered.
        ++update_failures_[*call->row];
        if (sync_.failed(*call, now_ms())) {
          const auto& row = kFleetNames[*call->row];
          log_record(spdlog::level::warn, "agones_update_failing",
                     {{"kind", to_string(row.kind)}, {"name", row.name}, {"call", op_name(call->op)},
                      {"status", o.status}, {"error", o.error}, {"retry_ms", sync_.retry(*call->row).backoff_ms()},
                      {"note", "retried with backoff; Ready and Health do not wait for it (is it declared in the "
                               "GameServer's spec?)"}});
        }
        if (o.status == 0) sidecar_failed();  // no answer at all: the sidecar is away, for every call
        lock.lock();
        continue;
      }
      // The call stays owed: the sidecar may still be starting.
      sidecar_failed();
      lock.lock();
      changed_cv_.wait_for(lock, ms(backoff_ms), [this] { return stop_; });
      backoff_ms = std::min(config_.retry_max_ms, backoff_ms * 2);
      continue;
    }
    if (Clock::now() >= next_poll) {
      lock.unlock();
      poll_gameserver();
      next_poll = Clock::now() + ms(config_.poll_ms);
      lock.lock();
      continue;
    }
    // Wake for a change, the next poll, or a failing Counter's or List's next try.
    auto until = next_poll;
    if (const auto retry = sync_.next_retry_ms(now_ms()))
      until = std::min(until, start + std::chrono::milliseconds(*retry));
    changed_cv_.wait_until(lock, until, [this] { return stop_ || changed_; });
    changed_ = false;
  }
}

// GET /gameserver (polling; the streaming /watch/gameserver would hold a second
// connection): logs each change of status.state, e.g. to Allocated.
void AgonesClient::poll_gameserver() {
  httplib::Client http(config_.host, config_.port);
  http.set_connection_timeout(0, 500000);
  http.set_read_timeout(1, 0);
  {
    std::lock_guard lock(mutex_);
    if (stop_) return;
    in_flight(&http);
  }
  const auto r = request(http, "GET", "/gameserver", "");
  in_flight(nullptr);
  if (!r || r->status != 200) return;
  // Whatever the answer holds: value() would throw on a state that is not a string, and
  // an exception here ends the process. Read strictly (a key twice is not an answer).
  std::string why;
  const auto parsed = room::parse_json(r->body, why);
  if (!parsed) return;
  const auto& j = *parsed;
  if (!j.is_object() || !j.contains("status") || !j["status"].is_object()) return;
  const auto& status = j["status"];
  if (!status.contains("state") || !status["state"].is_string()) return;
  const auto state = status["state"].get<std::string>();
  std::lock_guard lock(mutex_);
  if (state == gs_state_) return;
  gs_state_ = state;
  log_record(spdlog::level::info, "agones_state", {{"state", state}});
}

}  // namespace fts::server
