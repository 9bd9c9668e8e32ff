// Fixed ticks on integer time (Quake III's SV_Frame): tick k is due at
// start + k * 1e9 / rate ns, computed exactly, so there is no drift. When the process
// falls behind, at most `max_catch_up` late ticks run back to back; the rest are skipped
// (counted) and the schedule moves on, so a stall never makes the game run fast.
#pragma once

#include <cstdint>

namespace fts::server {

class TickClock {
 public:
  TickClock(std::uint32_t tick_rate_hz, std::uint32_t max_catch_up);

  void start(std::int64_t now_ns);
  // Ticks to run now (0 .. max_catch_up); call again after running them.
  std::uint32_t due(std::int64_t now_ns);
  // When the next tick is due (ns, same clock as now_ns).
  std::int64_t next_deadline_ns() const { return time_of(next_); }
  std::uint64_t skipped() const { return skipped_; }
  std::uint64_t ticks_run() const { return run_; }

 private:
  std::int64_t time_of(std::uint64_t k) const {
    return origin_ns_ + static_cast<std::int64_t>((k * 1'000'000'000ull) / rate_hz_);
  }

  std::uint32_t rate_hz_;
  std::uint32_t max_catch_up_;
  std::int64_t origin_ns_ = 0;
  std::uint64_t next_ = 0;  // index (since origin) of the next tick to run
  std::uint64_t skipped_ = 0;
  std::uint64_t run_ = 0;
};

}  // namespace fts::server
