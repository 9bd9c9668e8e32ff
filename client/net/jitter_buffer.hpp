// The interpolation delay of remote balls, sized from the link (issue 28): a jitter
// buffer. Remote balls are drawn `delay` behind the server clock's estimate, between the
// two snapshots around that time; if the delay is too short for the link, the newer one
// has not arrived yet and the balls stall (or are extrapolated); too long, and they lag.
//
// The delay is one snapshot interval, plus the lateness of arrivals (how far behind the
// server clock a snapshot of the last 3 s came: its 95th percentile; the buffer keeps that
// clock, so what the remote balls are drawn behind is what their delay was measured
// against), plus one more interval for each snapshot lost in a row recently (a lost
// snapshot leaves a gap of two intervals to bridge), plus a small margin, at most 1 s. It moves toward that target gradually (up
// by at most 25 % of the time that passes, down by at most 5 %), so the drawn clock never
// runs backwards nor jumps. A fixed delay (--interp-delay-ms) turns it off.
// Pure: arrivals and times are passed in.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

#include "net/interpolate.hpp"

namespace fts::client {

class JitterBuffer {
 public:
  JitterBuffer() = default;
  // Ticks per second, and snapshots every this many ticks.
  void set_rates(double tick_rate_hz, double ticks_per_snapshot);
  // A fixed delay instead (nothing adapts).
  void set_fixed(double ms) { fixed_ms_ = ms; delay_ms_ = ms; }
  bool fixed() const { return fixed_ms_.has_value(); }

  // A snapshot of `tick` arrived at now_ms (the clock follows the window's least
  // delayed arrival).
  void on_snapshot(std::uint32_t tick, std::uint64_t now_ms);
  // The server clock the lateness is measured against: draw `delay_ms()` behind it.
  const ServerClock& clock() const { return clock_; }
  // The delay to draw with at now_ms (slewed toward target()).
  double delay_ms(std::uint64_t now_ms);
  double target_ms() const;
  double jitter_ms() const { return jitter_ms_; }  // p95 lateness
  int burst() const { return burst_; }             // snapshots lost in a row, recently

 private:
  double tick_rate_hz_ = 100, ticks_per_snapshot_ = 5;
  ServerClock clock_;
  std::optional<double> fixed_ms_;
  double delay_ms_ = 100;                // the current delay
  std::uint64_t last_ms_ = 0;            // when delay_ms() was last asked
  bool started_ = false;
  struct Arrival {
    std::uint64_t at_ms;
    std::uint32_t tick;
    double offset;      // the clock's reading were this arrival on time (ServerClock)
    double clock_then;  // the clock's tick at the arrival, as it read then
    int lost_before;
  };
  std::deque<Arrival> window_;           // the last 3 s of arrivals (the clock's too)
  std::uint32_t last_tick_ = 0;
  double jitter_ms_ = 0;
  int burst_ = 0;
};

}  // namespace fts::client
