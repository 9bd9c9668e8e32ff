// Event-driven collisions inside one tick: every ball-ball and ball-wall contact is
// found at its exact time of impact and processed in time order, so nothing tunnels
// and nothing overlaps, at any speed.
//
// Each ball keeps its own clock t_i inside the tick and is advanced lazily. Events are
// invalidated by per-ball stamps instead of being removed from the heap. All working
// memory is the world's (World::buffers). The broad
// phase indexes each ball's swept box for the whole tick (with a margin); a ball whose
// path leaves its box after a collision joins a small "escaped" list that every
// re-query also scans, which keeps the search complete without rebuilding the grid.
#include <algorithm>
#include <cmath>
#include <limits>

#include "fts/sim/collide.hpp"
#include "step_internal.hpp"

namespace fts::sim::detail {
namespace {

constexpr std::uint32_t kWallX = 0xffffff00u;
constexpr std::uint32_t kWallY = 0xffffff01u;
constexpr std::uint32_t kFall = 0xffffff02u;

// b is another ball's index or kWallX / kWallY / kFall.
using Event = TimedEvent;
struct Later {
  bool operator()(const Event& x, const Event& y) const {
    if (x.t != y.t) return x.t > y.t;
    if (x.a != y.a) return x.a > y.a;
    return x.b > y.b;
  }
};

// The event queue: a binary heap (earliest first) in a vector the world owns.
class EventHeap {
 public:
  explicit EventHeap(std::vector<Event>& storage) : v_(storage) { v_.clear(); }
  bool empty() const { return v_.empty(); }
  const Event& top() const { return v_.front(); }
  void push(const Event& e) {
    v_.push_back(e);
    std::push_heap(v_.begin(), v_.end(), Later{});
  }
  void pop() {
    std::pop_heap(v_.begin(), v_.end(), Later{});
    v_.pop_back();
  }
  void clear() { v_.clear(); }

 private:
  std::vector<Event>& v_;
};

// One tick's solve over the world's balls, working in the world's step buffers.
class Solver {
 public:
  Solver(World& world, const PhysicsSettings& s, double dt, StepReport& report)
      : world_(world), balls_(world.balls), dt_(dt), report_(report),
        grid_mode_(use_grid(s, world.balls.size())), t_(world.buffers.t), stamp_(world.buffers.stamp),
        alive_(world.buffers.alive), escaped_flag_(world.buffers.escaped_flag),
        escaped_(world.buffers.escaped), overlaps_(world.buffers.pairs), grid_(world.buffers.grid),
        heap_(world.buffers.heap), escaped_box_(world.buffers.escaped_box) {}
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  void run() {
    const std::size_t n = balls_.size();
    t_.assign(n, 0.0);
    stamp_.assign(n, 0);
    alive_.assign(n, 1);
    escaped_flag_.assign(n, 0);
    escaped_box_.resize(n);  // written when a ball escapes, read only after
    // Balls that start a tick overlapping (a generated pile, a respawn) are first
    // pushed apart; then every pair is searched again from clean positions.
    if (initial_events() && !overlaps_.empty()) {
      std::sort(overlaps_.begin(), overlaps_.end());
      for (auto [i, j] : overlaps_) {
        Ball& a = balls_[i];
        Ball& b = balls_[j];
        const double reach = a.radius + b.radius;
        const double d = length(b.pos - a.pos);
        if (d < reach) separate(a, b, contact_normal(a, b), reach - d);
      }
      if (world_.arena.boundary == Boundary::walls) clamp_all_into_walls();
      initial_events();
    }
    process();
    finish();
  }

 private:
  Vec2 pos_at(std::uint32_t i, double t) const { return balls_[i].pos + balls_[i].vel * (t - t_[i]); }

  void advance(std::uint32_t i, double t) {
    balls_[i].pos = pos_at(i, t);
    t_[i] = t;
  }

  Box path_box(std::uint32_t i, double margin_scale) const {
    const Ball& b = balls_[i];
    const Vec2 end = pos_at(i, dt_);
    // |vx| + |vy| bounds the speed from above without a square root.
    const double speed_margin = margin_scale * (std::fabs(b.vel.x) + std::fabs(b.vel.y)) * (dt_ - t_[i]);
    const double m = b.radius * (1.0 + 0.05 * margin_scale) + speed_margin;
    return {std::min(b.pos.x, end.x) - m, std::min(b.pos.y, end.y) - m,
            std::max(b.pos.x, end.x) + m, std::max(b.pos.y, end.y) + m};
  }

  // Builds the broad phase and the first events; returns whether overlaps were found.
  bool initial_events() {
    heap_.clear();
    overlaps_.clear();
    escaped_.clear();
    const std::uint32_t n = static_cast<std::uint32_t>(balls_.size());
    for (std::uint32_t i = 0; i < n; ++i) boundary_event(i);
    auto pair = [&](std::uint32_t i, std::uint32_t j) { pair_event(i, j, true); };
    if (grid_mode_) {
      std::vector<Box>& boxes = grid_.boxes();
      boxes.resize(n);
      for (std::uint32_t i = 0; i < n; ++i) boxes[i] = path_box(i, 0.5);
      grid_.build();
      grid_.for_each_overlapping_pair(pair);
    } else {
      for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = i + 1; j < n; ++j) pair(i, j);
    }
    return !overlaps_.empty();
  }

  void clamp_all_into_walls() {
    const Arena& a = world_.arena;
    for (Ball& b : balls_) {
      b.pos.x = std::clamp(b.pos.x, std::min(b.radius, a.width_u * 0.5), std::max(a.width_u - b.radius, a.width_u * 0.5));
      b.pos.y = std::clamp(b.pos.y, std::min(b.radius, a.height_u * 0.5), std::max(a.height_u - b.radius, a.height_u * 0.5));
    }
  }

  void pair_event(std::uint32_t i, std::uint32_t j, bool record_overlap) {
    if (i == j || !alive_[i] || !alive_[j]) return;
    const double t0 = std::max(t_[i], t_[j]);
    const Vec2 d = pos_at(j, t0) - pos_at(i, t0);
    const Vec2 w = balls_[j].vel - balls_[i].vel;
    const double reach = balls_[i].radius + balls_[j].radius;
    const double c = length_sq(d) - reach * reach;
    if (c < 0.0 && record_overlap && -c > 1e-9 * reach * reach) {
      overlaps_.emplace_back(std::min(i, j), std::max(i, j));
    }
    const double b = dot(d, w);
    if (!(b < 0.0)) return;  // not approaching
    double t;
    if (c <= 0.0) {
      t = t0;  // touching or overlapping and approaching: collide now
    } else {
      const double a = length_sq(w);
      const double disc = b * b - a * c;
      if (!(disc >= 0.0)) return;
      // The smaller root of a t^2 + 2 b t + c = 0, in the cancellation-free form.
      t = t0 + c / (-b + std::sqrt(disc));
    }
    if (!(t <= dt_)) return;
    const std::uint32_t lo = std::min(i, j), hi = std::max(i, j);
    heap_.push({t, lo, hi, stamp_[lo], stamp_[hi]});
  }

  void boundary_event(std::uint32_t i) {
    const Ball& b = balls_[i];
    const Arena& a = world_.arena;
    // Most balls cannot reach an edge this tick: skip the divisions for them.
    const double reach = std::fabs(b.vel.x) + std::fabs(b.vel.y);
    const double travel = reach * (dt_ - t_[i]);
    const double inset = a.boundary == Boundary::walls ? b.radius : 0.0;
    if (b.pos.x - travel > inset && b.pos.x + travel < a.width_u - inset && b.pos.y - travel > inset &&
        b.pos.y + travel < a.height_u - inset)
      return;
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t kind = kWallX;
    auto axis = [&](double p, double v, double lo, double hi, std::uint32_t k) {
      double t = best;
      if (v < 0.0) t = p <= lo ? 0.0 : (lo - p) / v;
      else if (v > 0.0) t = p >= hi ? 0.0 : (hi - p) / v;
      if (t < best) {
        best = t;
        kind = k;
      }
    };
    if (a.boundary == Boundary::walls) {
      axis(b.pos.x, b.vel.x, b.radius, a.width_u - b.radius, kWallX);
      axis(b.pos.y, b.vel.y, b.radius, a.height_u - b.radius, kWallY);
    } else {
      // Already off the platform (pushed out by a separation): it falls now, whatever
      // its velocity.
      if (!(b.pos.x >= 0.0 && b.pos.x <= a.width_u && b.pos.y >= 0.0 && b.pos.y <= a.height_u)) {
        heap_.push({t_[i], i, kFall, stamp_[i], 0});
        return;
      }
      axis(b.pos.x, b.vel.x, 0.0, a.width_u, kFall);
      axis(b.pos.y, b.vel.y, 0.0, a.height_u, kFall);
    }
    const double t = t_[i] + best;
    if (t <= dt_) heap_.push({t, i, kind, stamp_[i], 0});
  }

  // Events of ball i against everything it may meet in the rest of the tick.
  void refresh(std::uint32_t i) {
    boundary_event(i);
    if (!grid_mode_) {
      for (std::uint32_t j = 0; j < balls_.size(); ++j) pair_event(i, j, false);
      return;
    }
    const Box now = path_box(i, 0.0);
    if (!escaped_flag_[i] && !grid_.is_overflow(i)) {
      const Box& home = grid_.box(i);
      if (now.x0 < home.x0 || now.y0 < home.y0 || now.x1 > home.x1 || now.y1 > home.y1) {
        escaped_flag_[i] = 1;
        escaped_.push_back(i);
      }
    }
    // An escaped ball's path for the rest of the tick, kept until its next event (which
    // refreshes it again); the small margin covers rounding, so the test below skips
    // only pairs that cannot meet. Without it every refresh predicted against every
    // escaped ball, which grew with N x escapes (gas-100000: 3x the cost per body-step
    // of gas-10000).
    if (escaped_flag_[i]) escaped_box_[i] = path_box(i, 0.1);
    grid_.query(now, [&](std::uint32_t j) {
      if (escaped_flag_[j]) return;  // scanned below
      if (grid_.is_overflow(j) || overlaps(now, grid_.box(j))) pair_event(i, j, false);
    });
    for (std::uint32_t j : escaped_)
      if (overlaps(now, escaped_box_[j])) pair_event(i, j, false);
  }

  void process() {
    const std::uint64_t budget = 64 * static_cast<std::uint64_t>(balls_.size()) + 4096;
    std::uint64_t handled = 0;
    while (!heap_.empty()) {
      const Event e = heap_.top();
      heap_.pop();
      if (!alive_[e.a] || stamp_[e.a] != e.stamp_a) continue;
      if (e.b < kWallX && (!alive_[e.b] || stamp_[e.b] != e.stamp_b)) continue;
      if (++handled > budget) {
        ++report_.event_cap_hits;
        return;
      }
      if (e.b >= kWallX) {
        wall(e);
      } else {
        collide(e);
      }
    }
  }

  void wall(const Event& e) {
    advance(e.a, e.t);
    Ball& b = balls_[e.a];
    ++stamp_[e.a];
    if (e.b == kFall) {
      alive_[e.a] = 0;
      report_.fallen.push_back(b.id);
      return;
    }
    double& v = e.b == kWallX ? b.vel.x : b.vel.y;
    double& p = e.b == kWallX ? b.pos.x : b.pos.y;
    const double hi = (e.b == kWallX ? world_.arena.width_u : world_.arena.height_u) - b.radius;
    p = std::clamp(p, std::min(b.radius, hi), std::max(b.radius, hi));
    report_.wall_impulse += 2.0 * b.mass * std::fabs(v);
    ++report_.wall_hits;
    v = -v;
    refresh(e.a);
  }

  void collide(const Event& e) {
    advance(e.a, e.t);
    advance(e.b, e.t);
    Ball& a = balls_[e.a];
    Ball& b = balls_[e.b];
    if (!respond_elastic(a, b, contact_normal(a, b))) return;
    ++report_.collisions;
    report_.contacts.push_back({a.id, b.id});
    ++stamp_[e.a];
    ++stamp_[e.b];
    refresh(e.a);
    refresh(e.b);
  }

  void finish() {
    const std::uint32_t n = static_cast<std::uint32_t>(balls_.size());
    for (std::uint32_t i = 0; i < n; ++i)
      if (alive_[i]) advance(i, dt_);
    if (!report_.fallen.empty()) {  // only a fall ends a ball's life
      std::size_t out = 0;
      for (std::uint32_t i = 0; i < n; ++i)
        if (alive_[i]) balls_[out++] = balls_[i];
      balls_.resize(out);
    }
    if (report_.event_cap_hits > 0) {
      // Out of budget (a jammed pile): leave no ball outside the arena.
      apply_boundary(world_, report_);
    }
  }

  World& world_;
  std::vector<Ball>& balls_;
  double dt_;
  StepReport& report_;
  bool grid_mode_;
  std::vector<double>& t_;
  std::vector<std::uint32_t>& stamp_;
  std::vector<std::uint8_t>& alive_;
  std::vector<std::uint8_t>& escaped_flag_;
  std::vector<std::uint32_t>& escaped_;
  std::vector<IndexPair>& overlaps_;
  Grid& grid_;
  EventHeap heap_;
  std::vector<Box>& escaped_box_;
};

}  // namespace

void step_continuous(World& world, const PhysicsSettings& s, double dt, StepReport& report) {
  Solver(world, s, dt, report).run();
}

}  // namespace fts::sim::detail
