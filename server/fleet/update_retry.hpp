// The retry state of one Counter's or List's updates (sans-I/O: time is passed in, in ms
// of the caller's clock). A failed update is tried again after a backoff that doubles per
// failure from min_ms up to max_ms; meanwhile the other calls (Ready, Health, labels, the
// other Counters and Lists) go on, so an undeclared Counter never holds Ready back. A
// spell is the failures in a row: its first is logged and its end (the update taken).
#pragma once

#include <algorithm>
#include <cstdint>

namespace fts::server {

class UpdateRetry {
 public:
  static constexpr std::uint32_t kDefaultMinMs = 100;
  // A Counter the GameServer does not declare stays undeclared until the pod is replaced:
  // after a few fast tries, one attempt every 5 s costs the sidecar nothing and still
  // finds a sidecar that comes back soon after it does.
  static constexpr std::uint32_t kDefaultMaxMs = 5000;

  explicit UpdateRetry(std::uint32_t min_ms = kDefaultMinMs, std::uint32_t max_ms = kDefaultMaxMs)
      : min_ms_(std::max<std::uint32_t>(1, min_ms)), max_ms_(std::max(min_ms_, max_ms)), backoff_ms_(min_ms_) {}

  // Whether an update may be tried at now_ms.
  bool due(std::uint64_t now_ms) const { return spell_ == 0 || now_ms >= next_ms_; }
  // An update failed at now_ms: the next try waits backoff_ms(). True when this failure
  // starts a spell (the one to log).
  bool failed(std::uint64_t now_ms) {
    const bool first = spell_++ == 0;
    if (first) {
      spell_start_ms_ = now_ms;
      backoff_ms_ = min_ms_;
    } else {
      backoff_ms_ = static_cast<std::uint32_t>(std::min<std::uint64_t>(max_ms_, std::uint64_t{backoff_ms_} * 2));
    }
    next_ms_ = now_ms + backoff_ms_;
    ++total_;
    return first;
  }
  // An update was taken: ends the spell; returns its failures (0: there was none).
  std::uint64_t succeeded() {
    const std::uint64_t n = spell_;
    spell_ = 0;
    backoff_ms_ = min_ms_;
    return n;
  }

  bool failing() const { return spell_ > 0; }
  std::uint64_t spell() const { return spell_; }            // failures in the current spell
  std::uint64_t total() const { return total_; }            // failures ever
  std::uint64_t next_ms() const { return next_ms_; }        // when a failing update is due
  std::uint64_t spell_start_ms() const { return spell_start_ms_; }
  std::uint32_t backoff_ms() const { return backoff_ms_; }  // the wait after the last failure

 private:
  std::uint32_t min_ms_, max_ms_;
  std::uint32_t backoff_ms_;
  std::uint64_t spell_ = 0, total_ = 0;
  std::uint64_t next_ms_ = 0, spell_start_ms_ = 0;
};

}  // namespace fts::server
