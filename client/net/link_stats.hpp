// What the link and the prediction did in a session, for `fts-client --stats-file` and
// the impairment matrix (BENCHMARKS.md, issue 28): remote-ball stalls (frames drawn with no
// snapshot newer than the drawn time: the other balls freeze, then jump when one comes),
// the prediction's corrections, and the link's figures. Pure.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "predict/prediction.hpp"

namespace fts::client {

class StallMeter {
 public:
  // One drawn frame at now_ms: stalled or not.
  void frame(bool stalled, std::uint64_t now_ms);
  std::uint64_t stalls() const { return stalls_; }            // episodes of 2 frames or more
  std::uint64_t over_100ms() const { return over_100ms_; }
  std::uint64_t longest_ms() const { return longest_ms_; }
  std::uint64_t stalled_ms() const { return stalled_ms_; }

 private:
  bool in_ = false;
  int frames_ = 0;
  std::uint64_t since_ms_ = 0, stalls_ = 0, over_100ms_ = 0, longest_ms_ = 0, stalled_ms_ = 0;
};

// The program's own view of its input latency: from a frame whose thrust changed to the
// first drawn frame where the own ball's velocity shows it (predicting: the next frame or
// so; from snapshots: a round trip and the interpolation delay later). The outside view,
// a key to the first moved cell on screen, is tests/bench/input_latency.py's.
// A velocity "shows the thrust" when it has moved toward the thrust by more than 1.5 u/s
// beyond what the game's friction alone (0.991 per 10 ms) would have made of it.
class ResponseMeter {
 public:
  // The thrust decided this frame; `drawn_v`: the own ball's drawn velocity (u/s).
  void thrust(int dx, int dy, double vx, double vy, std::uint64_t now_ms);
  void drawn(double vx, double vy, std::uint64_t now_ms);
  const std::vector<double>& samples_ms() const { return samples_; }

 private:
  int dx_ = 0, dy_ = 0;
  bool pending_ = false;
  double vx_ = 0, vy_ = 0;
  std::uint64_t since_ms_ = 0;
  std::vector<double> samples_;
};

// The p-th percentile (0..100) of `v` (0 when empty).
double percentile(std::vector<double> v, double p);

struct LinkSummary {
  bool predict = true;
  PredictionStats prediction;
  StallMeter stalls;
  ResponseMeter response;
  std::uint64_t duration_ms = 0;
  double rtt_ms = 0, loss_percent = 0, jitter_ms = 0, delay_ms = 0;
  std::uint64_t bytes_sent = 0, bytes_received = 0, frames = 0;
  std::uint64_t longest_gap_ms = 0;  // the longest time between two snapshots' arrivals
  double jitter_max_ms = 0;          // the highest p95 lateness seen (jitter_ms is the last)
};

// One JSON object (the keys are the matrix's columns).
std::string link_stats_json(const LinkSummary& s);

// Writes --stats-file's figures whole: to PATH.tmp, then renamed over PATH, so that a
// reader never sees half a file (fts-client writes them every second and at exit).
bool write_stats_file(const std::string& path, const std::string& json);

}  // namespace fts::client
