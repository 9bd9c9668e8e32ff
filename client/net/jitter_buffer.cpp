#include "net/jitter_buffer.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace fts::client {

namespace {
constexpr std::uint64_t kWindowMs = 3000;
constexpr double kMarginMs = 5;
// The delay grows by at most a quarter of the time passing (the drawn clock slows to 75 %:
// better than a stall) and shrinks by at most 5 % (it speeds up by 5 %, unseen).
constexpr double kSlewUp = 0.25, kSlewDown = 0.05;
constexpr int kMaxBurst = 3;       // intervals allowed for losses in a row
}  // namespace

void JitterBuffer::set_rates(double tick_rate_hz, double ticks_per_snapshot) {
  tick_rate_hz_ = tick_rate_hz > 0 ? tick_rate_hz : 100;
  ticks_per_snapshot_ = ticks_per_snapshot > 0 ? ticks_per_snapshot : 5;
}

void JitterBuffer::on_snapshot(std::uint32_t tick, std::uint64_t now_ms) {
  const double tick_ms = static_cast<double>(tick) * 1000.0 / tick_rate_hz_;
  const double offset = static_cast<double>(now_ms) - tick_ms;  // larger: later
  int lost = 0;
  if (!started_ || tick + 1000 < last_tick_) {  // the first, or the server started again
    started_ = true;
    best_offset_ms_ = offset;
    window_.clear();
  } else if (tick > last_tick_) {
    lost = std::max(0, static_cast<int>(std::lround((tick - last_tick_) / ticks_per_snapshot_)) - 1);
  } else {
    return;  // old or duplicate: says nothing new about the link
  }
  // The least delayed arrival is the reference; it creeps up by 1 ms a second (0.1 % of
  // the time), so that a clock running slower than the server's is followed too.
  best_offset_ms_ = std::min(best_offset_ms_ + 0.001 * 1000.0 / tick_rate_hz_ * ticks_per_snapshot_, offset);
  last_tick_ = std::max(last_tick_, tick);
  window_.push_back({now_ms, offset - best_offset_ms_, lost});
  while (!window_.empty() && window_.front().at_ms + kWindowMs < now_ms) window_.pop_front();
  std::vector<double> late;
  late.reserve(window_.size());
  burst_ = 0;
  for (const auto& a : window_) {
    late.push_back(a.late_ms);
    burst_ = std::max(burst_, a.lost_before);
  }
  const auto p95 = late.begin() + static_cast<std::ptrdiff_t>((late.size() - 1) * 95 / 100);
  std::nth_element(late.begin(), p95, late.end());
  jitter_ms_ = *p95;
}

double JitterBuffer::target_ms() const {
  if (fixed_ms_) return *fixed_ms_;
  const double interval_ms = ticks_per_snapshot_ * 1000.0 / tick_rate_hz_;
  return interval_ms * (1 + std::min(burst_, kMaxBurst)) + jitter_ms_ + kMarginMs;
}

double JitterBuffer::delay_ms(std::uint64_t now_ms) {
  if (fixed_ms_) return *fixed_ms_;
  const double passed = last_ms_ == 0 || now_ms < last_ms_ ? 0.0 : static_cast<double>(now_ms - last_ms_);
  last_ms_ = now_ms;
  const double target = target_ms();
  if (!started_) return delay_ms_;
  delay_ms_ = delay_ms_ < target ? std::min(target, delay_ms_ + kSlewUp * passed)
                                 : std::max(target, delay_ms_ - kSlewDown * passed);
  return delay_ms_;
}

}  // namespace fts::client
