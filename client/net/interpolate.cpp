#include "net/interpolate.hpp"

#include <algorithm>
#include <cmath>

namespace fts::client {

Snapshot interpolate(const Snapshot& a, const Snapshot& b, double alpha) {
  alpha = std::clamp(std::isfinite(alpha) ? alpha : 0.0, 0.0, 1.0);
  Snapshot out = b;
  auto ia = a.balls.begin();
  for (auto& ball : out.balls) {
    // Both lists are sorted by id: walk a alongside.
    while (ia != a.balls.end() && ia->id < ball.id) ++ia;
    if (ia == a.balls.end() || ia->id != ball.id || ia->kind != ball.kind) continue;
    ball.x = ia->x + (ball.x - ia->x) * alpha;
    ball.y = ia->y + (ball.y - ia->y) * alpha;
    ball.vx = ia->vx + (ball.vx - ia->vx) * alpha;
    ball.vy = ia->vy + (ball.vy - ia->vy) * alpha;
  }
  return out;
}

namespace {
constexpr double kFollowDown = 0.05;  // the clock slows to 95 % at most: unseen
}  // namespace

void ServerClock::start(double offset, std::uint64_t now_ms) {
  offset_ = offset;
  valid_ = true;
  last_ms_ = now_ms;
}

void ServerClock::follow(double best_offset, std::uint64_t now_ms) {
  if (best_offset >= offset_) {
    offset_ = best_offset;  // a less delayed arrival: follow it at once
  } else {
    const double elapsed = static_cast<double>(now_ms - std::min(now_ms, last_ms_));
    offset_ = std::max(best_offset, offset_ - elapsed * tick_rate_hz_ / 1000.0 * kFollowDown);
  }
  last_ms_ = now_ms;
}

double ServerClock::tick_at(std::uint64_t now_ms) const {
  if (!valid_) return 0;
  return offset_ + static_cast<double>(now_ms) * tick_rate_hz_ / 1000.0;
}

void SnapshotBuffer::push(Snapshot snapshot) {
  if (!snapshots_.empty() && snapshot.tick <= snapshots_.back().tick) {
    // A lower tick after a server restart starts afresh; an old one is dropped.
    if (snapshots_.back().tick - snapshot.tick < 1000) return;
    snapshots_.clear();
  }
  snapshots_.push_back(std::move(snapshot));
  while (snapshots_.size() > capacity_) snapshots_.pop_front();
}

Frame SnapshotBuffer::sample(double render_tick) const {
  Frame f;
  if (snapshots_.empty()) return f;
  if (render_tick <= snapshots_.front().tick) {
    f.a = f.b = &snapshots_.front();
    return f;
  }
  if (render_tick >= snapshots_.back().tick) {
    f.a = f.b = &snapshots_.back();
    return f;
  }
  for (std::size_t i = 1; i < snapshots_.size(); ++i) {
    const Snapshot& b = snapshots_[i];
    if (render_tick <= b.tick) {
      const Snapshot& a = snapshots_[i - 1];
      f.a = &a;
      f.b = &b;
      f.alpha = (render_tick - a.tick) / static_cast<double>(b.tick - a.tick);
      return f;
    }
  }
  f.a = f.b = &snapshots_.back();
  return f;
}

}  // namespace fts::client
