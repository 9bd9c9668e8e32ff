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
// Never more than this behind: a client starved of CPU reads its snapshots late and took
// that for a late link; its delay grew to 8 s, and enemies were drawn where they had been
// 8 s before beside the predicted own ball (new_player_e2e, 2026-12-07). Past a second the
// remote balls are extrapolated or wait instead.
constexpr double kMaxDelayMs = 1000;
constexpr double kRestartSeconds = 2;  // an arrival this far off the clock starts afresh
}  // namespace

void JitterBuffer::set_rates(double tick_rate_hz, double ticks_per_snapshot) {
  tick_rate_hz_ = tick_rate_hz > 0 ? tick_rate_hz : 100;
  ticks_per_snapshot_ = ticks_per_snapshot > 0 ? ticks_per_snapshot : 5;
  clock_ = ServerClock(tick_rate_hz_);
}

void JitterBuffer::on_snapshot(std::uint32_t tick, std::uint64_t now_ms) {
  const double offset = clock_.offset_of(tick, now_ms);
  int lost = 0;
  // The one restart rule of the buffer and its clock: the first arrival; a tick far below
  // the newest (the server started again); or a newer one more than 2 s off the clock (a
  // server that jumped, or a clock that was wrong). An old tick says nothing new.
  const bool restart = !started_ || tick + 1000 < last_tick_ ||
                       (tick > last_tick_ && clock_.seconds_off(offset) > kRestartSeconds);
  if (restart) {
    started_ = true;
    window_.clear();
    clock_.start(offset, now_ms);
  } else if (tick > last_tick_) {
    lost = std::max(0, static_cast<int>(std::lround((tick - last_tick_) / ticks_per_snapshot_)) - 1);
  } else {
    return;  // old or duplicate: says nothing new about the link
  }
  last_tick_ = tick;
  window_.push_back({now_ms, tick, offset, 0.0, lost});
  while (window_.front().at_ms + kWindowMs < now_ms) window_.pop_front();
  double best = offset;
  for (const auto& a : window_) best = std::max(best, a.offset);
  clock_.follow(best, now_ms);
  window_.back().clock_then = clock_.tick_at(now_ms);
  // Lateness against the clock the balls are drawn behind: how far behind it each
  // snapshot of the window came, the later of the clock as it read then and as it reads
  // now. The clock follows the window's least delayed arrival, not the session's: a
  // server that falls behind its schedule (a loaded host skips ticks, and its tick count
  // then runs slower than the clock) moves every later arrival back for good, which
  // against the session's best read as lateness growing without end (1.8 s after a minute
  // through the 150 ms relay on a busy machine, 2026-12-06). Against the clock as it read
  // at each arrival, such a server's lateness is what it slips in 3 s, for every arrival
  // alike (against the clock of now, the older ones would look on time and the 95th
  // percentile would miss the newest: stalls); against the clock of now, a clock that
  // moved up to a less delayed arrival counts at once for every arrival.
  std::vector<double> late;
  late.reserve(window_.size());
  burst_ = 0;
  for (const auto& a : window_) {
    const double expected = std::max(a.clock_then, clock_.tick_at(a.at_ms));
    late.push_back(std::max(0.0, (expected - a.tick) * 1000.0 / tick_rate_hz_));
    burst_ = std::max(burst_, a.lost_before);
  }
  const auto p95 = late.begin() + static_cast<std::ptrdiff_t>((late.size() - 1) * 95 / 100);
  std::nth_element(late.begin(), p95, late.end());
  jitter_ms_ = *p95;
}

double JitterBuffer::target_ms() const {
  if (fixed_ms_) return *fixed_ms_;
  const double interval_ms = ticks_per_snapshot_ * 1000.0 / tick_rate_hz_;
  return std::min(kMaxDelayMs, interval_ms * (1 + std::min(burst_, kMaxBurst)) + jitter_ms_ + kMarginMs);
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
