#include "app/tick_clock.hpp"

namespace fts::server {

TickClock::TickClock(std::uint32_t tick_rate_hz, std::uint32_t max_catch_up)
    : rate_hz_(tick_rate_hz == 0 ? 1 : tick_rate_hz), max_catch_up_(max_catch_up == 0 ? 1 : max_catch_up) {}

void TickClock::start(std::int64_t now_ns) {
  origin_ns_ = now_ns;
  next_ = 0;
}

std::uint32_t TickClock::due(std::int64_t now_ns) {
  if (now_ns < time_of(next_)) return 0;
  // Late ticks: k in [next_, last] are all due.
  const std::uint64_t elapsed = static_cast<std::uint64_t>(now_ns - origin_ns_);
  const std::uint64_t last = (elapsed * rate_hz_) / 1'000'000'000ull;
  std::uint64_t n = last - next_ + 1;
  if (n > max_catch_up_) {
    skipped_ += n - max_catch_up_;
    // Re-anchor the schedule at the oldest tick we still run, so tick spacing is kept.
    origin_ns_ = now_ns - static_cast<std::int64_t>(((max_catch_up_ - 1) * 1'000'000'000ull) / rate_hz_);
    next_ = 0;
    n = max_catch_up_;
  }
  next_ += n;
  run_ += n;
  return static_cast<std::uint32_t>(n);
}

}  // namespace fts::server
