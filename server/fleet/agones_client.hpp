// The Agones SDK REST client on its own thread: the tick loop hands it the wanted state
// (want(), never blocks beyond a mutex), the thread makes the calls AgonesSync says are
// owed, retrying with backoff while the sidecar starts late or answers 5xx (never fatal;
// a Counter or List it does not take is retried on its own, beside the other calls),
// and polls GET /gameserver to learn the server's Agones state (Allocated, ...).
// Every call is bounded whatever the sidecar does: a watchdog thread cuts off a call
// still running after timeout_ms (a sidecar that answers a byte at a time would
// otherwise hold the thread, and the process's exit, for ever), and an answer's body
// beyond kMaxBodyBytes ends the call (a garbage Content-Length is not buffered).
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "fleet/agones_sync.hpp"

namespace httplib {
class Client;
}

namespace fts::server {

struct AgonesClientConfig {
  std::string host = "127.0.0.1";  // the sidecar listens on localhost
  std::uint16_t port = 9358;
  std::uint32_t retry_min_ms = 100;   // first wait after a failed call; doubles per failure
  std::uint32_t retry_max_ms = 2000;  // cap of that wait
  std::uint32_t poll_ms = 1000;       // GET /gameserver period
  std::uint32_t timeout_ms = 2000;    // the longest one call may take, all told
  // A Counter's or List's update the sidecar does not take (an undeclared one: 500) is
  // retried on its own backoff beside the other calls (UpdateRetry), never ahead of them.
  std::uint32_t update_retry_min_ms = UpdateRetry::kDefaultMinMs;
  std::uint32_t update_retry_max_ms = UpdateRetry::kDefaultMaxMs;
};

class AgonesClient {
 public:
  explicit AgonesClient(AgonesClientConfig config);
  ~AgonesClient();  // stops the thread (an in-flight call is cut off at once)
  AgonesClient(const AgonesClient&) = delete;
  AgonesClient& operator=(const AgonesClient&) = delete;

  // The state to bring the sidecar to; the latest replaces any earlier one.
  void want(const AgonesWanted& wanted);
  bool shutdown_sent() const { return shutdown_sent_.load(); }
  bool ready_sent() const { return ready_sent_.load(); }
  // Calls not answered at all, and Ready, Health, labels or Shutdown answered 5xx, so far.
  std::uint64_t failures() const { return failures_.load(); }
  // Updates of kFleetNames[row] the sidecar did not take, so far (each retried).
  std::uint64_t update_failures(std::size_t row) const { return update_failures_.at(row).load(); }
  static constexpr std::size_t kMaxBodyBytes = 1 << 20;  // a GameServer object is a few KiB
  // status.state of the last GET /gameserver ("" before the first answer).
  std::string gameserver_state() const;

 private:
  void run();
  void poll_gameserver();
  void watch();  // the watchdog thread
  // Registers (nullptr: clears) the call being made on `http`.
  void in_flight(httplib::Client* http);

  AgonesClientConfig config_;
  mutable std::mutex mutex_;
  std::condition_variable changed_cv_;
  AgonesWanted wanted_;       // guarded by mutex_
  bool changed_ = false;      // guarded by mutex_
  bool stop_ = false;         // guarded by mutex_
  std::string gs_state_;      // guarded by mutex_
  // The watchdog's, apart from mutex_ (which want() takes): it may wait in
  // Client::stop() while a connect is under way.
  std::mutex watch_mutex_;
  std::condition_variable watch_cv_;
  httplib::Client* in_flight_ = nullptr;            // guarded by watch_mutex_: the call being made
  std::chrono::steady_clock::time_point deadline_;  // guarded by watch_mutex_: when it is cut off
  bool abort_ = false;                              // guarded by watch_mutex_: stopping, cut it off now
  bool watch_stop_ = false;                         // guarded by watch_mutex_
  AgonesSync sync_;           // the thread's own
  std::atomic<bool> shutdown_sent_{false};
  std::atomic<bool> ready_sent_{false};
  std::atomic<std::uint64_t> failures_{0};
  std::array<std::atomic<std::uint64_t>, kFleetNameCount> update_failures_{};
  std::thread thread_;
  std::thread watchdog_;
};

}  // namespace fts::server
