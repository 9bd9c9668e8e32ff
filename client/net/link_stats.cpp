#include "net/link_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace fts::client {

void StallMeter::frame(bool stalled, std::uint64_t now_ms) {
  if (stalled && !in_) {
    in_ = true;
    frames_ = 0;
    since_ms_ = now_ms;
  }
  if (stalled) ++frames_;
  if (!stalled && in_) {
    in_ = false;
    const std::uint64_t ms = now_ms - since_ms_;
    stalled_ms_ += ms;
    if (frames_ >= 2) ++stalls_;
    if (ms > 100) ++over_100ms_;
    longest_ms_ = std::max(longest_ms_, ms);
  }
}

namespace {
// Over the friction's cut-off (a component under 1 u/s stops) and under one tick of
// thrust (200 u/s^2 for 10 ms: 2 u/s).
constexpr double kShown = 1.5;
}  // namespace

void ResponseMeter::thrust(int dx, int dy, double vx, double vy, std::uint64_t now_ms) {
  if (dx == dx_ && dy == dy_) return;
  dx_ = dx;
  dy_ = dy;
  if (dx == 0 && dy == 0) return;  // letting go: friction, no response to time
  pending_ = true;
  vx_ = vx;
  vy_ = vy;
  since_ms_ = now_ms;
}

void ResponseMeter::drawn(double vx, double vy, std::uint64_t now_ms) {
  if (!pending_) return;
  if (now_ms - since_ms_ > 2000) {  // never shown (a wall of vmax, a fall): no sample
    pending_ = false;
    return;
  }
  // Friction alone since the key: v0 * 0.991^(ms / 10) (a measurement, not the match).
  const double coast = std::pow(0.991, static_cast<double>(now_ms - since_ms_) / 10.0);
  if ((vx - vx_ * coast) * dx_ > kShown || (vy - vy_ * coast) * dy_ > kShown) {
    pending_ = false;
    samples_.push_back(static_cast<double>(now_ms - since_ms_));
    if (samples_.size() > 100000) samples_.erase(samples_.begin(), samples_.begin() + 50000);
  }
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  // Nearest rank: the smallest value with at least p % of the values at or below it.
  const double rank = std::ceil(std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(v.size()));
  const auto i = static_cast<std::size_t>(std::max(rank, 1.0)) - 1;
  return v[std::min(i, v.size() - 1)];
}

std::string link_stats_json(const LinkSummary& s) {
  const double minutes = std::max(1e-9, static_cast<double>(s.duration_ms) / 60000.0);
  const auto& p = s.prediction;
  char buf[1536];
  std::snprintf(buf, sizeof buf,
                "{\"predict\":%s,\"duration_s\":%.1f,\"frames\":%llu,\"rtt_ms\":%.1f,\"loss_percent\":%.2f,"
                "\"jitter_ms\":%.1f,\"delay_ms\":%.1f,\"corrections\":%llu,\"snaps\":%llu,\"contact_corrections\":%llu,"
                "\"corrections_per_min\":%.2f,\"correction_p50_radii\":%.4f,\"correction_p99_radii\":%.4f,"
                "\"free_correction_p50_radii\":%.4f,\"free_correction_p99_radii\":%.4f,"
                "\"contact_correction_p50_radii\":%.4f,\"contact_correction_p99_radii\":%.4f,\"stalls\":%llu,"
                "\"stalls_per_min\":%.2f,\"stalls_over_100ms\":%llu,\"longest_stall_ms\":%llu,\"bytes_sent\":%llu,"
                "\"bytes_received\":%llu,\"up_bytes_per_s\":%.0f,\"down_bytes_per_s\":%.0f,\"responses\":%zu,"
                "\"response_p50_ms\":%.1f,\"response_p99_ms\":%.1f}",
                s.predict ? "true" : "false", static_cast<double>(s.duration_ms) / 1000.0,
                static_cast<unsigned long long>(s.frames), s.rtt_ms, s.loss_percent, s.jitter_ms, s.delay_ms,
                static_cast<unsigned long long>(p.corrections), static_cast<unsigned long long>(p.snaps),
                static_cast<unsigned long long>(p.contact_corrections),
                static_cast<double>(p.corrections + p.snaps) / minutes, percentile(p.all_sizes_radii, 50),
                percentile(p.all_sizes_radii, 99), percentile(p.free_sizes_radii, 50), percentile(p.free_sizes_radii, 99),
                percentile(p.contact_sizes_radii, 50), percentile(p.contact_sizes_radii, 99),
                static_cast<unsigned long long>(s.stalls.stalls()), static_cast<double>(s.stalls.stalls()) / minutes,
                static_cast<unsigned long long>(s.stalls.over_100ms()),
                static_cast<unsigned long long>(s.stalls.longest_ms()), static_cast<unsigned long long>(s.bytes_sent),
                static_cast<unsigned long long>(s.bytes_received),
                static_cast<double>(s.bytes_sent) / std::max(1e-9, static_cast<double>(s.duration_ms) / 1000.0),
                static_cast<double>(s.bytes_received) / std::max(1e-9, static_cast<double>(s.duration_ms) / 1000.0),
                s.response.samples_ms().size(), percentile(s.response.samples_ms(), 50),
                percentile(s.response.samples_ms(), 99));
  std::string out(buf);
  out.pop_back();  // the samples themselves, for a reader who wants the distribution
  out += ",\"longest_snapshot_gap_ms\":" + std::to_string(s.longest_gap_ms);
  char jitter_max[32];
  std::snprintf(jitter_max, sizeof jitter_max, ",\"jitter_max_ms\":%.1f", s.jitter_max_ms);
  out += jitter_max;
  out += ",\"response_samples_ms\":[";
  const auto& r = s.response.samples_ms();
  for (std::size_t i = 0; i < r.size() && i < 200; ++i) out += (i ? "," : "") + std::to_string(static_cast<long long>(r[i]));
  return out + "]}";
}

bool write_stats_file(const std::string& path, const std::string& json) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << json << "\n";
    if (!out.flush()) return false;
  }
  return std::rename(tmp.c_str(), path.c_str()) == 0;
}

}  // namespace fts::client
