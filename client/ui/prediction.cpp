#include "ui/prediction.hpp"

#include <algorithm>
#include <cmath>

#include "fts/sim/thrust.hpp"

namespace fts::client {

namespace {
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

void OwnBallPredictor::step_once() {
  if (!fallen_ && !world_.balls.empty()) {
    const auto [dx, dy] = input_at(cache_tick_);
    sim::apply_thrust(world_.balls.front(), dx, dy, accel_, vmax_, step_k_.dt_s);
    sim::StepReport report;
    sim::step(world_, physics_, step_k_, report);
    fallen_ = world_.balls.empty();
  }
  ++cache_tick_;
}

const sim::Ball* OwnBallPredictor::state_at(std::int64_t tick) {
  if (!base_) return nullptr;
  tick = std::clamp(tick, base_tick_, base_tick_ + static_cast<std::int64_t>(kMaxAheadS * tick_rate_hz_));
  if (tick < cache_tick_) {  // behind the cache (the shown tick went back): from the base
    world_.balls = {*base_};
    cache_tick_ = base_tick_;
    fallen_ = false;
  }
  while (cache_tick_ < tick) step_once();
  return fallen_ || world_.balls.empty() ? nullptr : &world_.balls.front();
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
    offset_x_ = offset_y_ = 0;
    return;
  }
  // Where the ball was drawn (before this snapshot), to measure the correction against.
  std::optional<protocol::BallState> drawn;
  const bool same_ball = base_ && base_->id.value == own->id;
  if (same_ball) drawn = at(shown_tick, now_ms);
  const std::int64_t previous_tick = base_tick_;
  sim::Ball b;
  b.id = own->id;
  b.pos = {own->x, own->y};
  b.vel = {own->vx, own->vy};
  b.radius = own->radius;
  b.mass = own->mass;
  base_ = b;
  base_tick_ = s.tick;
  accel_ = player->accel_u_per_s2;
  vmax_ = player->vmax_u_per_s;
  world_.balls = {b};
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
  if (!touching) stats_.free_sizes_radii.push_back(radii);
  if (touching) ++stats_.contact_corrections;
  if (radii > k_.snap_radii) {
    ++stats_.snaps;
    offset_x_ = offset_y_ = 0;  // a big one is taken at once: the ball is elsewhere
    return;
  }
  ++stats_.corrections;
  offset_x_ += ex;  // drawn where it was; the offset decays toward the new prediction
  offset_y_ += ey;
  for (auto* v : {&stats_.all_sizes_radii, &stats_.free_sizes_radii})
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
