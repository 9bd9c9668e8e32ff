#include "predict/prediction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fts/sim/level.hpp"
#include "fts/sim/rng.hpp"
#include "fts/sim/thrust.hpp"

namespace fts::client {

namespace {
// A snapshot's ball as the physics' (id, position, velocity, radius, mass).
sim::Ball ball_of(const protocol::BallState& b) {
  sim::Ball ball;
  ball.id = b.id;
  ball.pos = {b.x, b.y};
  ball.vel = {b.vx, b.vy};
  ball.radius = b.radius;
  ball.mass = b.mass;
  return ball;
}

// Never predict more than this past the base, in the server's ticks (200 at 100 Hz; a
// fixed 200 ticks was 10 s at 20 Hz).
constexpr double kMaxAheadS = 2.0;

// The configuration as given when the step can run on it (a server's always can: it
// validated it); else the defaults. The welcome's ranges let friction 0 through, which
// no valid configuration has and on which the friction factor is not defined.
sim::MatchConfig steppable(const sim::MatchConfig& cfg) {
  const bool ok = cfg.tick_rate_hz >= 1.0 && cfg.frame_s > 0.0 && cfg.friction_per_frame > 0.0 &&
                  cfg.friction_per_frame <= 1.0 && cfg.friction_cutoff_u_per_s >= 0.0 && cfg.substeps >= 1 &&
                  cfg.substeps <= 1024;
  return ok ? cfg : sim::MatchConfig{};
}
}  // namespace

double LeadClock::predicted(double server_tick, double rtt_ms, double jitter_ms, double tick_rate_hz,
                            std::uint64_t now_ms) {
  const double target = (std::max(rtt_ms, 0.0) + std::max(jitter_ms, 0.0) + kMarginMs) * tick_rate_hz / 1000.0 + 1.0;
  const double passed = last_ms_ == 0 ? 0.0 : static_cast<double>(now_ms - std::min(now_ms, last_ms_)) * tick_rate_hz / 1000.0;
  last_ms_ = now_ms;
  if (lead_ticks_ == 0) lead_ticks_ = target;
  else if (lead_ticks_ < target) lead_ticks_ = std::min(target, lead_ticks_ + 0.5 * passed);
  else lead_ticks_ = std::max(target, lead_ticks_ - 0.1 * passed);
  return server_tick + lead_ticks_;
}

std::uint32_t LeadClock::stamp(double predicted_tick) {
  if (std::isfinite(predicted_tick)) stamp_ = std::max(stamp_, static_cast<std::int64_t>(std::floor(predicted_tick)));
  return static_cast<std::uint32_t>(std::clamp<std::int64_t>(stamp_, 1, 0xffffffffll));
}

OwnBallPredictor::OwnBallPredictor(const sim::MatchConfig& given, PredictionTuning tuning) : k_(tuning) {
  const sim::MatchConfig cfg = steppable(given);
  cfg_ = cfg;
  // The match's own settings and constants (match.cpp make_match()).
  physics_ = sim::physics_settings(cfg);
  step_k_ = sim::make_step_constants(physics_, 1.0 / cfg.tick_rate_hz);
  tick_rate_hz_ = cfg.tick_rate_hz;
  world_.arena.width_u = cfg.arena_width_u;
  world_.arena.height_u = cfg.arena_height_u;
  world_.arena.boundary = sim::Boundary::open;
}

void OwnBallPredictor::input(std::int64_t tick, int dx, int dy) {
  inputs_[tick] = {std::clamp(dx, -1, 1), std::clamp(dy, -1, 1)};
  // Older entries than the base's are not needed again, but the one in force at it is.
  while (inputs_.size() > 2 && std::next(inputs_.begin())->first <= base_tick_) inputs_.erase(inputs_.begin());
  while (inputs_.size() > 4096) inputs_.erase(inputs_.begin());
}

std::pair<int, int> OwnBallPredictor::input_at(std::int64_t tick) const {
  auto it = inputs_.upper_bound(tick);
  if (it == inputs_.begin()) return {0, 0};
  return std::prev(it)->second;
}

const sim::Ball* OwnBallPredictor::own_in_cache() const {
  if (fallen_ || !base_) return nullptr;
  const auto& balls = world_.balls;
  auto it = std::lower_bound(balls.begin(), balls.end(), base_->id, [](const sim::Ball& b, sim::BallId v) { return b.id < v; });
  return it != balls.end() && it->id == base_->id ? &*it : nullptr;
}

void OwnBallPredictor::step_once() {
  if (!fallen_ && !world_.balls.empty()) {
    // As the match's tick (match_play.cpp): thrust, the protected balls immovable for the
    // step, then the step (moves, collisions, friction, falls).
    const double dt = step_k_.dt_s;
    bool any_fixed = false;
    for (sim::Ball& b : world_.balls) {
      auto m = std::lower_bound(movers_.begin(), movers_.end(), b.id.value,
                                [](const Mover& x, std::uint32_t v) { return x.id < v; });
      if (m == movers_.end() || m->id != b.id.value) continue;
      if (m->own) {
        const auto [dx, dy] = input_at(cache_tick_);
        if (dx != 0 || dy != 0) m->protected_until = -1;  // acting ends the protection
        sim::apply_thrust(b, dx, dy, accel_, vmax_, dt);
      } else if (m->accel > 0) {
        sim::thrust_axis(b.vel.x, m->dx, m->accel, m->vmax, dt);
        sim::thrust_axis(b.vel.y, m->dy, m->accel, m->vmax, dt);
        b.thrust_axes = static_cast<std::uint8_t>((m->dx != 0 ? sim::kThrustX : 0) | (m->dy != 0 ? sim::kThrustY : 0));
      }
      if (cache_tick_ < m->protected_until) {
        b.mass = std::numeric_limits<double>::infinity();
        any_fixed = true;
      }
    }
    sim::StepReport report;
    sim::step(world_, physics_, step_k_, report);
    if (any_fixed)
      for (sim::Ball& b : world_.balls)
        if (std::isinf(b.mass))
          for (const sim::Ball& o : base_world_)
            if (o.id == b.id) b.mass = o.mass;
    stats_.balls_stepped += world_.balls.size();
    ++stats_.ticks_stepped;
    fallen_ = own_in_cache() == nullptr;
  }
  ++cache_tick_;
}

const sim::Ball* OwnBallPredictor::state_at(std::int64_t tick) {
  if (!base_) return nullptr;
  tick = std::clamp(tick, base_tick_, base_tick_ + static_cast<std::int64_t>(kMaxAheadS * tick_rate_hz_));
  if (tick < cache_tick_) {  // behind the cache (the shown tick went back): from the base
    world_.balls = base_world_;
    movers_ = base_movers_;
    cache_tick_ = base_tick_;
    fallen_ = false;
  }
  while (cache_tick_ < tick) step_once();
  return own_in_cache();
}

std::vector<protocol::BallState> OwnBallPredictor::others_at(double tick) {
  std::vector<protocol::BallState> out;
  if (!base_ || !std::isfinite(tick)) return out;
  const auto whole = static_cast<std::int64_t>(std::floor(tick));
  if (state_at(whole) == nullptr) return out;
  const double frac = std::clamp(tick - static_cast<double>(std::max(whole, base_tick_)), 0.0, 1.0) / tick_rate_hz_;
  for (const sim::Ball& b : world_.balls) {
    if (b.id == base_->id) continue;
    protocol::BallState o;
    o.id = b.id.value;
    o.x = b.pos.x + b.vel.x * frac;
    o.y = b.pos.y + b.vel.y * frac;
    o.vx = b.vel.x;
    o.vy = b.vel.y;
    o.radius = b.radius;
    o.mass = b.mass;
    out.push_back(o);
  }
  return out;
}

int OwnBallPredictor::fit_axis(double v0, double v1, std::int64_t n, double accel, double vmax, int held) const {
  int best = held;
  double best_err = std::numeric_limits<double>::infinity();
  for (int d : {held, -1, 0, 1}) {  // the held one first: it wins a tie
    double v = v0;
    for (std::int64_t i = 0; i < n; ++i) {
      sim::thrust_axis(v, d, accel, vmax, step_k_.dt_s);
      if (physics_.friction) {
        v *= step_k_.friction_factor;
        if (d == 0 && std::fabs(v) < physics_.friction_cutoff_u_per_s) v = 0.0;
      }
    }
    const double err = std::fabs(v - v1);
    if (err < best_err) best = d, best_err = err;
  }
  // Nothing explains it within half a tick's thrust (and the wire's rounding): a collision
  // changed the velocity; the direction held before stays.
  return best_err <= 0.5 * accel * step_k_.dt_s + 0.13 ? best : held;
}

void OwnBallPredictor::choose_others(const protocol::Snapshot& s, const protocol::BallState& own,
                                     const protocol::PlayerState& me) {
  // Enemies thrust with their level's acceleration and top speed (the same for every
  // enemy of a level; the welcome's configuration, the defaults for what it lacks).
  sim::Rng scratch(0);
  const sim::EnemySpec spec = sim::enemy_spec(std::max<std::int64_t>(s.level, 1), 0, scratch, cfg_);
  const bool still = spec.role == sim::EnemyRole::still;
  const std::int64_t n = static_cast<std::int64_t>(s.tick) - prev_tick_;
  const bool fit = prev_tick_ >= 0 && n >= 1 && n <= 50;
  std::map<std::uint32_t, std::pair<int, int>> held;
  std::vector<std::pair<double, Mover>> near;
  std::vector<sim::Ball> balls;
  for (const auto& b : s.balls) {
    if (b.id == own.id) continue;
    Mover m;
    m.id = b.id;
    if (b.kind == protocol::BallKind::enemy && !still) {
      m.accel = spec.accel_u_per_s2;
      m.vmax = spec.vmax_u_per_s;
    } else if (b.kind == protocol::BallKind::player) {
      for (const auto& p : s.players)
        if (p.id == b.owner) {
          m.accel = p.accel_u_per_s2;
          m.vmax = p.vmax_u_per_s;
          if (p.protected_until_tick > s.tick) m.protected_until = p.protected_until_tick;
        }
    }
    if (m.accel > 0) {
      // Held: the fit's, else (first sight) an enemy heads where it moves, a player idles.
      auto h = held_.find(b.id);
      std::pair<int, int> d{0, 0};
      if (h != held_.end()) d = h->second;
      else if (b.kind == protocol::BallKind::enemy) d = {b.vx > 0 ? 1 : (b.vx < 0 ? -1 : 0), b.vy > 0 ? 1 : (b.vy < 0 ? -1 : 0)};
      if (fit) {
        auto pb = std::lower_bound(prev_balls_.begin(), prev_balls_.end(), b.id,
                                   [](const protocol::BallState& x, std::uint32_t v) { return x.id < v; });
        if (pb != prev_balls_.end() && pb->id == b.id) {
          d.first = fit_axis(pb->vx, b.vx, n, m.accel, m.vmax, d.first);
          d.second = fit_axis(pb->vy, b.vy, n, m.accel, m.vmax, d.second);
        }
      }
      held[b.id] = d;
      m.dx = d.first;
      m.dy = d.second;
      if (m.protected_until >= 0 && (d.first != 0 || d.second != 0)) m.protected_until = -1;
    }
    const bool remote = b.kind == protocol::BallKind::player;
    if (remote && k_.remote == RemotePlayers::off) continue;
    if (remote && k_.remote == RemotePlayers::coast) m.dx = m.dy = 0;
    const double gap = std::hypot(b.x - own.x, b.y - own.y) - b.radius - own.radius;
    if (k_.others && gap <= k_.near_gap_u) near.emplace_back(gap, m);
  }
  held_ = std::move(held);
  prev_balls_ = s.balls;
  std::sort(prev_balls_.begin(), prev_balls_.end(), [](const auto& x, const auto& y) { return x.id < y.id; });
  prev_tick_ = s.tick;
  const std::size_t keep = static_cast<std::size_t>(std::max(k_.max_others, 0));
  if (near.size() > keep) {
    std::nth_element(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(keep), near.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first || (a.first == b.first && a.second.id < b.second.id); });
    near.resize(keep);
  }
  Mover self;
  self.id = own.id;
  self.own = true;
  if (me.protected_until_tick > s.tick) self.protected_until = me.protected_until_tick;
  base_movers_ = {self};
  for (const auto& [gap, m] : near) base_movers_.push_back(m);
  std::sort(base_movers_.begin(), base_movers_.end(), [](const Mover& a, const Mover& b) { return a.id < b.id; });
  base_world_.clear();
  for (const auto& m : base_movers_) {
    auto b = std::find_if(s.balls.begin(), s.balls.end(), [&](const protocol::BallState& x) { return x.id == m.id; });
    base_world_.push_back(ball_of(*b));
  }
}

double OwnBallPredictor::offset_factor(std::uint64_t now_ms) const {
  const double age = static_cast<double>(now_ms > offset_ms_ ? now_ms - offset_ms_ : 0);
  return k_.blend_ms > 0 ? std::exp(-age / k_.blend_ms) : 0.0;  // the screen's, not the match's
}

void OwnBallPredictor::on_snapshot(const protocol::Snapshot& s, std::uint32_t me, double shown_tick,
                                   std::uint64_t now_ms) {
  const protocol::BallState* own = nullptr;
  for (const auto& b : s.balls)
    if (b.kind == protocol::BallKind::player && b.owner == me) own = &b;
  const protocol::PlayerState* player = nullptr;
  for (const auto& p : s.players)
    if (p.id == me) player = &p;
  if (own == nullptr || player == nullptr || s.phase != protocol::Phase::play) {
    base_.reset();
    base_world_.clear();
    offset_x_ = offset_y_ = 0;
    prev_balls_ = s.balls;
    std::sort(prev_balls_.begin(), prev_balls_.end(), [](const auto& x, const auto& y) { return x.id < y.id; });
    prev_tick_ = s.tick;
    return;
  }
  // Where the ball was drawn (before this snapshot), to measure the correction against.
  std::optional<protocol::BallState> drawn;
  const bool same_ball = base_ && base_->id.value == own->id;
  if (same_ball) drawn = at(shown_tick, now_ms);
  const std::int64_t previous_tick = base_tick_;
  base_ = ball_of(*own);
  base_tick_ = s.tick;
  accel_ = player->accel_u_per_s2;
  vmax_ = player->vmax_u_per_s;
  choose_others(s, *own, *player);
  world_.balls = base_world_;
  movers_ = base_movers_;
  cache_tick_ = base_tick_;
  fallen_ = false;
  if (!drawn) {  // a new ball (respawn, first sight): nothing to correct
    offset_x_ = offset_y_ = 0;
    return;
  }
  const double keep = offset_factor(now_ms);
  offset_x_ *= keep;
  offset_y_ *= keep;
  offset_ms_ = now_ms;
  const auto now_pred = at(shown_tick, now_ms);  // with the decayed offset, from the new base
  if (!now_pred) return;
  const double ex = drawn->x - now_pred->x, ey = drawn->y - now_pred->y;
  const double size_u = std::sqrt(ex * ex + ey * ey);
  if (size_u < k_.tiny_u) return;
  const double radii = size_u / std::max(own->radius, 1e-6);
  // Touched since the last snapshot: another ball is within the distance both could have
  // covered since then (a contact between snapshots leaves them apart again by now).
  const double since_s = static_cast<double>(s.tick - std::min<std::int64_t>(s.tick, previous_tick)) / tick_rate_hz_;
  bool touching = false;
  for (const auto& o : s.balls) {
    if (o.id == own->id) continue;
    const double speeds = std::hypot(o.vx, o.vy) + std::hypot(own->vx, own->vy);
    const double dx = o.x - own->x, dy = o.y - own->y, reach = o.radius + own->radius + 4.0 + speeds * since_s;
    touching = touching || dx * dx + dy * dy <= reach * reach;
  }
  stats_.all_sizes_radii.push_back(radii);
  (touching ? stats_.contact_sizes_radii : stats_.free_sizes_radii).push_back(radii);
  if (touching) ++stats_.contact_corrections;
  if (radii > k_.snap_radii) {
    ++stats_.snaps;
    offset_x_ = offset_y_ = 0;  // a big one is taken at once: the ball is elsewhere
    return;
  }
  ++stats_.corrections;
  offset_x_ += ex;  // drawn where it was; the offset decays toward the new prediction
  offset_y_ += ey;
  for (auto* v : {&stats_.all_sizes_radii, &stats_.free_sizes_radii, &stats_.contact_sizes_radii})
    if (v->size() > 100000) v->erase(v->begin(), v->begin() + 50000);
}

std::optional<protocol::BallState> OwnBallPredictor::at(double tick, std::uint64_t now_ms) {
  if (!base_ || !std::isfinite(tick)) return std::nullopt;
  const auto whole = static_cast<std::int64_t>(std::floor(tick));
  const sim::Ball* b = state_at(whole);
  if (b == nullptr) return std::nullopt;
  const double frac = std::clamp(tick - static_cast<double>(std::max(whole, base_tick_)), 0.0, 1.0);
  const double keep = offset_factor(now_ms);
  protocol::BallState out;
  out.id = b->id.value;
  out.x = b->pos.x + b->vel.x * frac / tick_rate_hz_ + offset_x_ * keep;
  out.y = b->pos.y + b->vel.y * frac / tick_rate_hz_ + offset_y_ * keep;
  out.vx = b->vel.x;
  out.vy = b->vel.y;
  out.radius = b->radius;
  out.mass = b->mass;
  out.kind = protocol::BallKind::player;
  return out;
}

}  // namespace fts::client
