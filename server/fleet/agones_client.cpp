#include "fleet/agones_client.hpp"

#include <algorithm>
#include <chrono>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "app/log.hpp"

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

Outcome send(httplib::Client& http, const SdkCall& c) {
  httplib::Result r = c.method == "PATCH" ? http.Patch(c.path, c.body, "application/json")
                      : c.method == "PUT" ? http.Put(c.path, c.body, "application/json")
                                          : http.Post(c.path, c.body, "application/json");
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

AgonesClient::AgonesClient(AgonesClientConfig config) : config_(std::move(config)), thread_([this] { run(); }) {}

AgonesClient::~AgonesClient() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_cv_.notify_all();
  thread_.join();
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
  auto next_poll = Clock::now();
  std::unique_lock lock(mutex_);
  while (!stop_) {
    const AgonesWanted wanted = wanted_;
    if (const auto call = sync_.next(wanted)) {
      lock.unlock();
      const Outcome o = send(http, *call);
      if (o.done) {
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
      // Not answered, or a 5xx: the sidecar may still be starting. The call stays owed.
      const auto n = ++failures_;
      if (n == 1 || n % 20 == 0)
        log_record(spdlog::level::warn, "agones_retry",
                   {{"call", op_name(call->op)}, {"status", o.status}, {"error", o.error}, {"failures", n},
                    {"retry_ms", backoff_ms}});
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
    changed_cv_.wait_until(lock, next_poll, [this] { return stop_ || changed_; });
    changed_ = false;
  }
}

// GET /gameserver (polling; the streaming /watch/gameserver would hold a second
// connection): logs each change of status.state, e.g. to Allocated.
void AgonesClient::poll_gameserver() {
  httplib::Client http(config_.host, config_.port);
  http.set_connection_timeout(0, 500000);
  http.set_read_timeout(1, 0);
  const auto r = http.Get("/gameserver");
  if (!r || r->status != 200) return;
  const auto j = nlohmann::json::parse(r->body, nullptr, false);
  if (j.is_discarded() || !j.contains("status") || !j["status"].is_object()) return;
  const auto state = j["status"].value("state", std::string());
  std::lock_guard lock(mutex_);
  if (state == gs_state_) return;
  gs_state_ = state;
  log_record(spdlog::level::info, "agones_state", {{"state", state}});
}

}  // namespace fts::server
