// Event-driven collisions inside one tick: every ball-ball and ball-wall contact is
// found at its exact time of impact and processed in time order, so nothing tunnels
// and nothing overlaps, at any speed.
//
// Each ball keeps its own clock t_i inside the tick and is advanced lazily. Events are
// invalidated by per-ball stamps instead of being removed from the heap. The solve works
// on a copy of the balls (StepBuffers::bodies: clock, stamp and what an event needs in
// one cache line), refreshed from the world where it changed and written back at the
// end. All working memory is the world's (World::buffers).
//
// The broad phase is a skin, kept across ticks (a Verlet list, as molecular dynamics
// codes keep one): each ball's skin is the disc of radius + half_skin around its position
// at the last build, and the pairs whose skins overlap are listed once per build. A ball
// whose path in a tick stays within half_skin of where the skin was built can only meet
// its listed neighbours. A ball whose path leaves its skin (at the start of a tick, or
// after a collision) joins a small "escaped" list: it finds its partners with a query of
// the skin grid, and every other refresh also scans the list. When too many balls have
// left, or a ball was added, removed or resized, the skin is rebuilt (step_skin.cpp).
// Predictions are kept across ticks too: a listed pair found unable to meet for the
// next k ticks (k <= kMaxSkip) is not predicted again until then, unless one of its
// balls changes its line (an event, or a change between ticks). Which pairs are
// offered never changes a result, only its cost: every pair that can meet is predicted
// by the same formula and the heap orders events by (time, a, b), so a world stepped
// with or without its cache ends in the same bits.
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "fts/sim/collide.hpp"
#include "continuous_bounds.hpp"
#include "event_heap.hpp"
#include "step_internal.hpp"

namespace fts::sim::detail {
namespace {

// One tick's solve over the world's balls, working in the world's step buffers.
class Solver {
 public:
  Solver(World& world, const PhysicsSettings& s, double dt, StepReport& report)
      : world_(world), balls_(world.balls), dt_(dt), report_(report),
        grid_mode_(use_grid(s, world.balls.size())), bodies_(world.buffers.bodies), alive_(world.buffers.alive),
        escaped_flag_(world.buffers.escaped_flag), escaped_(world.buffers.escaped), overlaps_(world.buffers.pairs),
        grid_(world.buffers.grid), heap_(world.buffers.heap), escaped_box_(world.buffers.escaped_box),
        skin_(world.buffers) {}
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  void run() {
    const std::size_t n = balls_.size();
    // The working copies and liveness carry over from the last solve while the count of
    // balls stays: finish() leaves every clock at 0 and (no fall) every ball alive, and
    // a stamp is only compared with itself within one tick (the heap starts empty). A
    // copy that differs from its ball is refreshed before the events (initial_events).
    if (bodies_.size() != n) bodies_.assign(n, SolverBall{});
    if (skin_.course.size() != n) skin_.course.assign(n, 0);
    if (alive_.size() != n) alive_.assign(n, 1);
    clear_escaped();  // before the resize: the list may hold the last solve's indices
    escaped_flag_.resize(n);
    skin_.escaped_slot.resize(n);  // written when a ball escapes, read only after
    // Raw pointers into the buffers, which keep their size for the whole solve: through
    // the vectors every access reloads the data pointer (a store might alias it).
    B_ = bodies_.data();
    C_ = skin_.course.data();
    A_ = alive_.data();
    E_ = escaped_flag_.data();
    edges_ = {world_.arena.boundary == Boundary::walls, world_.arena.width_u, world_.arena.height_u};
    slack_ = 1e-12 * (std::fabs(world_.arena.width_u) + std::fabs(world_.arena.height_u));
    // Balls that start a tick overlapping (a generated pile, a respawn) are first
    // pushed apart; then every pair is searched again from clean positions.
    if (initial_events() && !overlaps_.empty()) {
      std::sort(overlaps_.begin(), overlaps_.end());
      separate_pairs(balls_, overlaps_);
      if (world_.arena.boundary == Boundary::walls) clamp_into_walls(balls_, world_.arena);
      world_.buffers.skin_valid = false;  // the balls moved
      initial_events();
    }
    process();
    finish();
  }

 private:
  Vec2 pos_at(std::uint32_t i, double t) const { return B_[i].pos + B_[i].vel * (t - B_[i].t); }

  void advance(std::uint32_t i, double t) {
    B_[i].pos = pos_at(i, t);
    B_[i].t = t;
  }

  BallId id_of(std::uint32_t i) const { return grid_mode_ ? BallId{skin_.skin_id[i]} : balls_[i].id; }
  // Every working copy from its ball (clock 0); course: changed in this solve.
  void copy_all_balls() {
    const std::uint32_t n = static_cast<std::uint32_t>(balls_.size());
    for (std::uint32_t i = 0; i < n; ++i) {
      const Ball& b = balls_[i];
      B_[i] = {b.pos, b.vel, b.radius, b.mass, 0.0, 0, 0};
      C_[i] = tick_;
    }
  }

  Box path_box(std::uint32_t i, double margin_scale) const { return box_of_path(B_[i], dt_, margin_scale); }

  // The first events of the tick; returns whether overlapping balls were found.
  bool initial_events() {
    heap_.clear();
    overlaps_.clear();
    clear_escaped();
    const std::uint32_t n = static_cast<std::uint32_t>(balls_.size());
    if (!grid_mode_) {
      copy_all_balls();
      initial_boundary_events();
      for (std::uint32_t i = 0; i < n; ++i)  // every ball is alive at the start of a solve
        for (std::uint32_t j = i + 1; j < n; ++j) predict(i, j, true);
      skin_.skin_valid = false;  // the wakes assume every solve saw the balls
      return !overlaps_.empty();
    }
    if (skin_.skin_tick >= (1u << 30)) skin_.skin_valid = false;  // renumbered by a build
    tick_ = ++skin_.skin_tick;
    const Fit fit = skin_fits();
    if (fit != Fit::fits) {
      if (fit == Fit::changed) copy_all_balls();
      build_continuous_skin(balls_, dt_, skin_);
      tick_ = skin_.skin_tick;
      const std::uint32_t* start = skin_.near_start.data();
      for (std::uint32_t i = 0; i < n; ++i) {
        // Every ball "changed" in the last solve: no earlier than any wake was seen, so
        // every pair is due now, and before this solve's, so pairs may sleep after it.
        C_[i] = tick_ - 1;
        B_[i].near = start[i];
      }
      // A crowded pass did every ball's course and edge tests; after a change they are
      // done again. Either way a ball faster than the new skin leaves it even now.
      if (fit == Fit::changed) skin_fits();
      escape_after_build();
    }
    for (std::uint32_t k = 0; k < edge_count_; ++k) edge_event(skin_.edge_due[k]);
    // Each pair once: listed pairs of balls in their skins, then each escaped ball
    // against the balls in their skins (a grid query) and the later escaped ones.
    // A pair predicted in an earlier tick whose balls both kept their lines since is
    // predicted again only when its wake comes (kept_apart_ticks).
    const std::size_t np = skin_.skin_pairs.size();
    const IndexPair* pairs = skin_.skin_pairs.data();
    StepBuffers::PairWake* wakes = skin_.pair_wake.data();
    const std::uint32_t* course = C_;
    const std::uint32_t tick = tick_;
    constexpr std::size_t kAhead = 16;
    for (std::size_t p = 0; p < np; ++p) {
      if (p + kAhead < np) {
        const auto [fi, fj] = pairs[p + kAhead];
        __builtin_prefetch(&course[fi]);
        __builtin_prefetch(&course[fj]);
        __builtin_prefetch(&B_[fi]);
        __builtin_prefetch(&B_[fj]);
      }
      const auto [i, j] = pairs[p];
      StepBuffers::PairWake& w = wakes[p];
      if (w.wake > tick && course[i] < w.seen && course[j] < w.seen) continue;
      if (E_[i] || E_[j]) continue;
      const std::uint32_t apart = kept_apart_ticks(i, j);
      w.seen = tick;
      w.wake = tick + (apart > 0 ? apart : 1);
      if (apart == 0) pair_event(i, j, true);
    }
    for (std::size_t k = 0; k < escaped_.size(); ++k) {
      const std::uint32_t i = escaped_[k];
      const Box now = path_box(i, 0.0);
      grid_.query(now, [&](std::uint32_t j) {
        if (!E_[j] && (grid_.is_overflow(j) || overlaps(now, grid_.box(j)))) pair_event(i, j, true);
      });
      for (std::size_t m = k + 1; m < escaped_.size(); ++m)
        if (overlaps(escaped_box_[k], escaped_box_[m])) pair_event(i, escaped_[m], true);
    }
    return !overlaps_.empty();
  }

  // Whether ball i's path for the rest of the tick stays within its skin.
  [[gnu::always_inline]] bool in_skin(std::uint32_t i) const {
    const double h = 0.99 * skin_.half_skin;
    return stays_within(B_[i].pos, B_[i].vel, dt_ - B_[i].t, skin_.skin_origin[i], h * h);
  }

  [[gnu::always_inline]] std::uint32_t kept_apart_ticks(std::uint32_t i, std::uint32_t j) const {
    return ticks_kept_apart(B_[i], B_[j], slack_, dt_);
  }

  // Escape flags are set only by escape(), which lists the ball: clearing the listed
  // ones clears them all.
  void clear_escaped() {
    for (std::uint32_t i : escaped_)
      if (i < escaped_flag_.size()) escaped_flag_[i] = 0;
    escaped_.clear();
    escaped_box_.clear();
  }

  void escape(std::uint32_t i) {
    E_[i] = 1;
    skin_.escaped_slot[i] = static_cast<std::uint32_t>(escaped_.size());
    escaped_.push_back(i);
    escaped_box_.push_back(path_box(i, 0.1));
  }

  enum class Fit { fits, crowded, changed };
  // Whether the skin still fits the balls: the same balls (else `changed`, at once), and
  // few enough of them leaving it this tick that the escaped list stays short (else
  // `crowded`: the pass goes on, escaping no more, so that its course and edge tests
  // still cover every ball and a rebuild needs only escape_after_build()). Those leaving
  // it are escaped.
  Fit skin_fits() {
    const std::size_t n = balls_.size();
    clear_escaped();
    edge_count_ = 0;
    if (!skin_.skin_valid || skin_.skin_id.size() != n || grid_.boxes().size() != n || skin_.skin_dt != dt_)
      return Fit::changed;
    const std::uint32_t tick = tick_;
    // The balls that may reach an edge, written branch-free into a list as long as the
    // balls (edge_count_ of them are real).
    skin_.edge_due.resize(n);
    std::uint32_t* due = skin_.edge_due.data();
    std::uint32_t edge_count = 0;
    const Edges edges = edges_;
    const std::size_t allowed = 32 + n / 256;
    bool crowded = false;
    const Ball* balls = balls_.data();
    SolverBall* body = B_;
    const std::uint32_t* ids = skin_.skin_id.data();
    const Vec2* origins = skin_.skin_origin.data();
    const double h = 0.99 * skin_.half_skin, h2 = h * h, dt = dt_;
    for (std::uint32_t i = 0; i < n; ++i) {
      const Ball& b = balls[i];
      SolverBall& w = body[i];  // its radius is the one the skin was built for
      if (b.id.value != ids[i] || b.radius != w.radius) return Fit::changed;
      // A ball whose position, velocity or mass is not what the last solve left was changed
      // from outside: its copy is refreshed and its course changed. Compared as bits: a
      // changed zero sign counts as a change, and so does any change of a NaN's bits.
      const Bits2 changed = (bits2(b.pos) ^ bits2(w.pos)) | (bits2(b.vel) ^ bits2(w.vel));
      const std::uint64_t mass = std::bit_cast<std::uint64_t>(b.mass) ^ std::bit_cast<std::uint64_t>(w.mass);
      if ((changed[0] | changed[1] | mass) != 0) {
        w.pos = b.pos;
        w.vel = b.vel;
        w.mass = b.mass;
        C_[i] = tick;
      }
      // in_skin(i) at the start of the tick (every clock is 0), without the reloads.
      if (!stays_within(b.pos, b.vel, dt, origins[i], h2)) {
        if (escaped_.size() == allowed) {
          crowded = true;
        } else {
          escape(i);
        }
      }
      due[edge_count] = i;  // boundary_event's test
      edge_count += clear_of_edges(b, dt, edges) ? 0u : 1u;
    }
    edge_count_ = edge_count;
    return crowded ? Fit::crowded : Fit::fits;
  }

  // After a build every origin is the ball's position: a ball leaves its new skin this
  // tick only if it travels more than (0.99 of) half a skin. All of them are escaped.
  void escape_after_build() {
    clear_escaped();
    const std::uint32_t n = static_cast<std::uint32_t>(balls_.size());
    const double h = 0.99 * skin_.half_skin, h2 = h * h, dt = dt_;
    for (std::uint32_t i = 0; i < n; ++i) {
      const double ex = B_[i].vel.x * dt, ey = B_[i].vel.y * dt;
      if (!(ex * ex + ey * ey <= h2)) escape(i);
    }
  }

  [[gnu::always_inline]] void pair_event(std::uint32_t i, std::uint32_t j, bool record_overlap) {
    if (i != j && A_[i] && A_[j]) predict(i, j, record_overlap);
  }

  // The pair's event, if they meet in the rest of the tick (two live balls).
  [[gnu::always_inline]] void predict(std::uint32_t i, std::uint32_t j, bool record_overlap) {
    const double t0 = std::max(B_[i].t, B_[j].t);
    const Vec2 d = pos_at(j, t0) - pos_at(i, t0);
    const Vec2 w = B_[j].vel - B_[i].vel;
    const double reach = B_[i].radius + B_[j].radius;
    const double c = length_sq(d) - reach * reach;
    if (c < 0.0 && record_overlap && -c > 1e-9 * reach * reach) {
      overlaps_.emplace_back(std::min(i, j), std::max(i, j));
    }
    const double b = dot(d, w);
    if (!(b < 0.0)) return;  // not approaching
    // Cannot meet in the rest of the tick, decided without the root and the division:
    // for t in [0, rest], |d + w t|^2 - reach^2 >= c + 2 b t >= c + 2 b rest, so c >
    // -2 b rest means no contact; the root below is then >= c / (-2 b) > rest too. The
    // slack (1e-9 of the tick) is far above the rounding of either computation, so only
    // pairs the formula would also reject are skipped.
    if (c > -2.0 * b * ((dt_ - t0) + 1e-9 * dt_)) return;
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
    heap_.push({t, lo, hi, B_[lo].stamp, B_[hi].stamp});
  }

  // boundary_event for every ball at the start of the tick (every clock 0), with the
  // arena and the tick in registers: the same test, the same events.
  // (grid mode does the same test in skin_fits' pass over the balls).
  void initial_boundary_events() {
    const std::uint32_t n = static_cast<std::uint32_t>(balls_.size());
    for (std::uint32_t i = 0; i < n; ++i)
      if (!clear_of_edges(B_[i], dt_, edges_)) edge_event(i);  // dt_ - 0
  }

  // Most balls cannot reach an edge this tick: an inlined test skips the divisions.
  void boundary_event(std::uint32_t i) {
    if (!clear_of_edges(B_[i], dt_ - B_[i].t, edges_)) edge_event(i);
  }

  [[gnu::noinline]] void edge_event(std::uint32_t i) {
    const SolverBall& b = B_[i];
    const EdgeHit hit = first_edge(b, world_.arena);
    const double t = b.t + hit.after;
    if (t <= dt_) heap_.push({t, i, hit.edge, b.stamp, 0});
  }

  // Events of ball i against everything it may meet in the rest of the tick.
  void refresh(std::uint32_t i) {
    boundary_event(i);
    if (!grid_mode_) {
      for (std::uint32_t j = 0; j < balls_.size(); ++j) pair_event(i, j, false);
      return;
    }
    const Box now = path_box(i, 0.0);
    if (E_[i]) {
      escaped_box_[skin_.escaped_slot[i]] = path_box(i, 0.1);  // its path until its next event
    } else if (!in_skin(i)) {
      escape(i);
    }
    if (E_[i]) {
      grid_.query(now, [&](std::uint32_t j) {
        if (!E_[j] && (grid_.is_overflow(j) || overlaps(now, grid_.box(j)))) pair_event(i, j, false);
      });
    } else {
      // The neighbours' lines are asked for together before the first is used (at 10^5
      // balls each is a miss; one after another they would wait in turn).
      const std::uint32_t* near = skin_.near.data() + B_[i].near;
      for (const std::uint32_t* k = near; *k != kEndOfNear; ++k) __builtin_prefetch(&B_[*k]);
      for (const std::uint32_t* k = near; *k != kEndOfNear; ++k) {
        const std::uint32_t j = *k;
        if (!E_[j]) pair_event(i, j, false);
      }
    }
    // An escaped ball's box holds its path until its next event (the small margin
    // covers rounding), so the test skips only pairs that cannot meet.
    const Box* boxes = escaped_box_.data();  // dense, in the list's order
    for (std::size_t k = 0; k < escaped_.size(); ++k)
      if (overlaps(now, boxes[k])) pair_event(i, escaped_[k], false);
  }

  void process() {
    const std::uint64_t budget = 64 * static_cast<std::uint64_t>(balls_.size()) + 4096;
    std::uint64_t handled = 0;
    while (!heap_.empty()) {
      const Event e = heap_.top();
      heap_.pop();
      if (!heap_.empty()) {  // the next event's balls, asked for while this one is handled
        const Event& next = heap_.top();
        __builtin_prefetch(&B_[next.a]);
        if (next.b < kWallX) __builtin_prefetch(&B_[next.b]);
      }
      if (!A_[e.a] || B_[e.a].stamp != e.stamp_a) continue;
      if (e.b < kWallX && (!A_[e.b] || B_[e.b].stamp != e.stamp_b)) continue;
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
    SolverBall& b = B_[e.a];
    C_[e.a] = tick_;
    ++b.stamp;
    if (e.b == kFall) {
      A_[e.a] = 0;
      report_.fallen.push_back(balls_[e.a].id);
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
    if (grid_mode_) {  // what refresh() reads next, asked for before the response
      for (std::uint32_t i : {e.a, e.b}) {
        __builtin_prefetch(&skin_.near[B_[i].near]);
        __builtin_prefetch(&skin_.skin_origin[i]);
      }
    }
    advance(e.a, e.t);
    advance(e.b, e.t);
    SolverBall& a = B_[e.a];
    SolverBall& b = B_[e.b];
    C_[e.a] = C_[e.b] = tick_;
    if (!respond_elastic(a, b, contact_direction(a.pos, b.pos))) return;
    ++report_.collisions;
    report_.contacts.push_back({id_of(e.a), id_of(e.b)});
    ++a.stamp;
    ++b.stamp;
    refresh(e.a);
    refresh(e.b);
  }

  void finish() {
    const std::uint32_t n = static_cast<std::uint32_t>(balls_.size());
    // Every ball to the end of the tick and back into the world; its copy's clock back to
    // 0, the copy being what the next solve compares the ball with (skin_fits).
    Ball* balls = balls_.data();
    for (std::uint32_t i = 0; i < n; ++i) {
      SolverBall& w = B_[i];
      if (A_[i]) w.pos = pos_at(i, dt_);
      w.t = 0.0;
      balls[i].pos = w.pos;
      balls[i].vel = w.vel;
    }
    if (!report_.fallen.empty()) {  // only a fall ends a ball's life
      skin_.skin_valid = false;       // the indices shift (the copies are made again)
      std::size_t out = 0;
      for (std::uint32_t i = 0; i < n; ++i)
        if (A_[i]) balls_[out++] = balls_[i];
      balls_.resize(out);
      alive_.clear();  // the next solve starts them all alive again (read above, cleared after)
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
  BigVector<SolverBall>& bodies_;
  BigVector<std::uint8_t>& alive_;
  BigVector<std::uint8_t>& escaped_flag_;
  std::vector<std::uint32_t>& escaped_;
  std::vector<IndexPair>& overlaps_;
  Grid& grid_;
  EventHeap heap_;
  std::vector<Box>& escaped_box_;
  StepBuffers& skin_;
  SolverBall* B_ = nullptr;
  std::uint32_t* C_ = nullptr;  // StepBuffers::course
  std::uint8_t* A_ = nullptr;
  std::uint8_t* E_ = nullptr;
  Edges edges_{};
  double slack_ = 0.0;       // kept_apart_ticks' margin for the arena's size
  std::uint32_t tick_ = 0;   // this solve's number (grid mode; StepBuffers::skin_tick)
  std::uint32_t edge_count_ = 0;  // StepBuffers::edge_due's length this solve
};

}  // namespace

void step_continuous(World& world, const PhysicsSettings& s, double dt, StepReport& report) {
  Solver(world, s, dt, report).run();
}

}  // namespace fts::sim::detail
