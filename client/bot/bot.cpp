#include "bot/bot.hpp"

#include <algorithm>
#include <cmath>

#include "fts/sim/bot_player.hpp"

namespace fts::bot {
namespace {

const char* event_name(protocol::EventKind k) {
  using K = protocol::EventKind;
  switch (k) {
    case K::enemy_fell: return "enemy_fell";
    case K::player_fell: return "player_fell";
    case K::level_started: return "level_started";
    case K::level_complete: return "level_complete";
    case K::purchase: return "purchase";
    case K::player_joined: return "player_joined";
    case K::player_left: return "player_left";
    case K::rocket_fired: return "rocket_fired";
    case K::match_over: return "game_over";
    case K::respawned: return "respawned";
    case K::interest: return "interest";
    case K::level_restarted: return "level_restarted";
    case K::count_: break;
  }
  return "?";
}

const char* phase_name(protocol::Phase p) {
  switch (p) {
    case protocol::Phase::lobby: return "lobby";
    case protocol::Phase::play: return "play";
    case protocol::Phase::shop: return "shop";
    case protocol::Phase::over: return "over";
  }
  return "?";
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

std::optional<Behavior> parse_behavior(const std::string& s) {
  if (s == "idle") return Behavior::idle;
  if (s == "wander") return Behavior::wander;
  if (s == "hunter") return Behavior::hunter;
  if (s == "shopper") return Behavior::shopper;
  return std::nullopt;
}

Bot::Bot(BotOptions options) : options_(std::move(options)), rng_(options_.seed), token_(options_.token) {}

void Bot::start(std::uint64_t now_ms) {
  protocol::ClientConfig c;
  c.encoding = options_.encoding;
  c.name = options_.name;
  c.token = token_;
  if (options_.protocol_version) c.version = options_.protocol_version;
  endpoint_.emplace(c);
  endpoint_->connect(now_ms);
}

void Bot::receive(std::span<const std::uint8_t> bytes, std::uint64_t now_ms) {
  if (endpoint_) endpoint_->receive(bytes, now_ms);
}

std::vector<std::vector<std::uint8_t>> Bot::take_datagrams() {
  return endpoint_ ? endpoint_->take_datagrams() : std::vector<std::vector<std::uint8_t>>{};
}

void Bot::fail(const std::string& why) {
  if (failure_.empty()) failure_ = why;
  errors_.push_back(why);
  finished_ = true;
}

const protocol::PlayerState* Bot::me() const {
  if (!latest_) return nullptr;
  for (const auto& p : latest_->players)
    if (p.id == player_id_) return &p;
  return nullptr;
}

double Bot::field(const std::string& name) const {
  const auto* p = me();
  if (name == "coins") return p ? static_cast<double>(p->coins) : NAN;
  if (name == "lives") return p ? p->lives : NAN;
  if (name == "mass") return p ? p->mass : NAN;
  if (name == "level") return latest_ ? latest_->level : NAN;
  if (name == "tick") return latest_ ? latest_->tick : NAN;
  if (name == "purchases") return static_cast<double>(purchases_ok_);
  return NAN;
}

void Bot::on_snapshot(const protocol::Snapshot& s) {
  if (snapshots_ == 0) first_tick_ = s.tick;
  ++snapshots_;
  last_tick_ = s.tick;
  for (const auto& e : s.events) {
    if (e.tick <= last_event_tick_) continue;
    new_events_.push_back(event_name(e.kind));
    // Coins as the events tell them, to check against the coins in the snapshot.
    if (e.kind == protocol::EventKind::enemy_fell && e.b == player_id_) earned_ += e.value;
    if (e.kind == protocol::EventKind::interest && e.a == player_id_) earned_ += e.value;
    if (e.kind == protocol::EventKind::purchase && e.a == player_id_) {
      spent_ += e.value;
      ++purchase_events_;
    }
  }
  for (const auto& e : s.events) last_event_tick_ = std::max(last_event_tick_, e.tick);
  if (s.phase != last_phase_) {
    sent_ready_for_phase_ = false;
    last_phase_ = s.phase;
  }
  latest_ = s;
}

void Bot::send_command(protocol::CommandOp op, char item, std::uint64_t now_ms) {
  pending_rid_ = endpoint_->send_command(op, item, now_ms);
  pending_op_ = op;
  pending_item_ = item;
}

protocol::InputFrame Bot::behave() {
  protocol::InputFrame f;
  if (!latest_ || latest_->phase != protocol::Phase::play) return f;
  const auto* p = me();
  if (!p || !p->alive) return f;
  const bool hunting = script_hunting_ || (options_.script.empty() &&
                                           (options_.behavior == Behavior::hunter || options_.behavior == Behavior::shopper));
  if (options_.script.empty() && options_.behavior == Behavior::wander) {
    if (latest_->tick >= wander_until_tick_) {
      wander_.move_x = static_cast<std::int8_t>(rng_.uniform_int(-1, 1));
      wander_.move_y = static_cast<std::int8_t>(rng_.uniform_int(-1, 1));
      wander_until_tick_ = latest_->tick + static_cast<std::uint64_t>(rng_.uniform_int(20, 80));
    }
    return wander_;
  }
  if (!hunting) return f;
  sim::BotSight sight;
  for (const auto& b : latest_->balls) {
    sim::Ball ball{b.id, {b.x, b.y}, {b.vx, b.vy}, b.radius, b.mass};
    if (b.kind == protocol::BallKind::player && b.owner == player_id_) sight.me = ball;
    else if (b.kind == protocol::BallKind::enemy) sight.enemies.push_back(ball);
  }
  if (sight.me.id == 0) return f;
  sight.vmax_u_per_s = p->vmax_u_per_s;
  sight.accel_u_per_s2 = p->accel_u_per_s2;
  sight.rockets = p->weapon == protocol::Weapon::rockets;
  if (const auto& w = endpoint_->welcome()) {
    sight.arena_width_u = w->arena_width_u;
    sight.arena_height_u = w->arena_height_u;
  }
  const sim::PlayerInput in = sim::bot_play_input(sight);
  f.move_x = in.move_x;
  f.move_y = in.move_y;
  f.fire = in.fire;
  return f;
}

void Bot::update(std::uint64_t now_ms) {
  now_ms_ = now_ms;
  if (!endpoint_ || finished_) return;
  endpoint_->update(now_ms);
  switch (endpoint_->state()) {
    case protocol::ClientState::refused: {
      const auto& e = endpoint_->error();
      fail("refused by the server: " + (e ? e->code + ": " + e->message : std::string("no reason")));
      return;
    }
    case protocol::ClientState::timed_out:
      fail(options_.probe ? "no answer from the server (timed out)" : "connection timed out");
      return;
    case protocol::ClientState::disconnected:
      if (!disconnected_by_script_) {
        const auto& e = endpoint_->error();
        fail("disconnected by the server" + (e ? ": " + e->code + ": " + e->message : std::string()));
        return;
      }
      break;
    default: break;
  }
  if (const auto& w = endpoint_->welcome()) {
    if (player_id_ == 0 || w->player_id != 0) player_id_ = w->player_id;
    token_ = w->token;
    ticks_per_snapshot_ = std::max<std::uint32_t>(1, w->tick_rate_hz / std::max<std::uint32_t>(1, w->snapshot_rate_hz));
  }
  for (auto& r : endpoint_->take_results()) {
    if (r.command_rid == pending_rid_) {
      pending_rid_ = 0;
      if (pending_op_ == protocol::CommandOp::buy) {
        (r.ok ? purchases_ok_ : purchases_refused_) += 1;
        if (r.ok) bought_.push_back(std::string(1, pending_item_));
      }
    }
    last_result_ = r;
  }
  for (auto& s : endpoint_->take_snapshots()) on_snapshot(s);
  if (now_ms - last_rtt_sample_ms_ >= 250 && endpoint_->state() == protocol::ClientState::connected) {
    const double rtt = endpoint_->stats().rtt_ms;
    if (rtt > 0) rtt_samples_.push_back(rtt);
    last_rtt_sample_ms_ = now_ms;
  }
  if (options_.probe) {
    if (snapshots_ > 0) finished_ = true;
    return;
  }
  if (!options_.script.empty()) {
    run_script(now_ms);
    new_events_.clear();
    if (finished_) return;
  } else if (latest_ && pending_rid_ == 0 && endpoint_->state() == protocol::ClientState::connected) {
    // Behaviors answer the phases: ready in the lobby and shop, the shopper buys first.
    const auto* p = me();
    const auto phase = latest_->phase;
    if (p && !p->ready && !sent_ready_for_phase_ && options_.behavior != Behavior::idle &&
        (phase == protocol::Phase::lobby || phase == protocol::Phase::shop) && latest_->tick > shop_wait_tick_) {
      std::optional<sim::Item> want;
      if (phase == protocol::Phase::shop && options_.behavior == Behavior::shopper) {
        sim::ShopSight s;
        s.coins = p->coins;
        s.lives = p->lives;
        s.bank = p->bank;
        s.accel_u_per_s2 = p->accel_u_per_s2;
        s.vmax_u_per_s = p->vmax_u_per_s;
        s.mass = static_cast<std::int64_t>(p->mass);
        s.prices = p->prices;  // both in item table order
        want = sim::bot_shop_choice(s);
      }
      if (want) {
        send_command(protocol::CommandOp::buy, sim::shop_key(*want), now_ms);
      } else {
        send_command(protocol::CommandOp::ready, 0, now_ms);
        sent_ready_for_phase_ = true;
      }
      shop_wait_tick_ = latest_->tick + 2 * ticks_per_snapshot_;  // decide again on fresh state
    }
    new_events_.clear();
  }
  // One input per server tick (by the clock; snapshots come slower than ticks).
  const std::uint64_t tick_ms = endpoint_->welcome() ? 1000 / std::max<std::uint32_t>(1, endpoint_->welcome()->tick_rate_hz) : 10;
  if (endpoint_->state() == protocol::ClientState::connected && latest_ && now_ms >= last_input_ms_ + tick_ms) {
    last_input_ms_ = now_ms;
    protocol::InputFrame f = options_.script.empty() || script_hunting_ ? behave() : script_hold_;
    if (fire_once_) {
      f.fire = true;
      fire_once_ = false;
    }
    endpoint_->send_input(f, now_ms);
  }
}

void Bot::run_script(std::uint64_t now_ms) {
  while (pc_ < options_.script.size() && !finished_) {
    const Step& s = options_.script[pc_];
    if (!step_started_) {
      step_started_ = true;
      command_sent_ = false;
      step_deadline_ms_ = now_ms + static_cast<std::uint64_t>(timeout_s_ * 1000);
      step_until_tick_ = (latest_ ? latest_->tick : 0) + static_cast<std::uint32_t>(std::max(0.0, s.number));
    }
    if (!step_script(s, now_ms)) {
      if (!finished_ && now_ms > step_deadline_ms_)
        fail("script line " + std::to_string(s.line) + " '" + s.text + "': no success within " +
             std::to_string(static_cast<int>(timeout_s_)) + " s");
      return;
    }
    ++pc_;
    step_started_ = false;
  }
  if (pc_ >= options_.script.size()) finished_ = true;
}

bool Bot::step_script(const Step& s, std::uint64_t now_ms) {
  const bool connected = endpoint_->state() == protocol::ClientState::connected;
  const std::uint32_t tick = latest_ ? latest_->tick : 0;
  switch (s.op) {
    case Step::Op::set_timeout: timeout_s_ = s.number; return true;
    case Step::Op::wait_event:
      if (s.word == "connected") return connected && latest_.has_value();
      return std::find(new_events_.begin(), new_events_.end(), s.word) != new_events_.end();
    case Step::Op::wait_phase: return latest_ && s.word == phase_name(latest_->phase);
    case Step::Op::wait_ticks: return latest_ && tick >= step_until_tick_;
    case Step::Op::move: {
      script_hunting_ = false;
      script_hold_ = {};
      if (s.word == "left") script_hold_.move_x = -1;
      if (s.word == "right") script_hold_.move_x = 1;
      if (s.word == "up") script_hold_.move_y = 1;
      if (s.word == "down") script_hold_.move_y = -1;
      if (tick < step_until_tick_) return false;
      script_hold_ = {};
      return true;
    }
    case Step::Op::hunt:
      if (s.number < 0) {
        script_hunting_ = true;
        return true;
      }
      script_hunting_ = tick < step_until_tick_;
      return !script_hunting_;
    case Step::Op::fire: fire_once_ = true; return true;
    case Step::Op::buy:
    case Step::Op::ready:
    case Step::Op::play_again:
      if (!connected) return false;
      if (!command_sent_) {
        const auto op = s.op == Step::Op::buy ? protocol::CommandOp::buy
                        : s.op == Step::Op::ready ? protocol::CommandOp::ready : protocol::CommandOp::play_again;
        send_command(op, s.op == Step::Op::buy ? s.word[0] : 0, now_ms);
        command_sent_ = true;
        return false;
      }
      return pending_rid_ == 0;
    case Step::Op::expect_result: {
      const bool ok = last_result_ && last_result_->ok;
      if ((s.word == "ok") != ok)
        fail("script line " + std::to_string(s.line) + " '" + s.text + "' failed: last result was " +
             (last_result_ ? (last_result_->ok ? "ok" : "refused (" + last_result_->code + ": " + last_result_->message + ")")
                           : std::string("none")));
      return true;
    }
    case Step::Op::expect_field: {
      // Judge on a snapshot newer than the step's start, so results are visible.
      if (!latest_ || latest_->tick < step_until_tick_ + ticks_per_snapshot_) return false;
      const double v = field(s.word);
      if (!compare(v, s.cmp, s.number))
        fail("script line " + std::to_string(s.line) + " '" + s.text + "' failed: " + s.word + " is " +
             (std::isnan(v) ? std::string("unknown") : std::to_string(static_cast<long long>(v))));
      return true;
    }
    case Step::Op::disconnect:
      disconnected_by_script_ = true;
      endpoint_->disconnect(now_ms, "script");
      return true;
    case Step::Op::reconnect:
      if (!reconnect_started_) {
        reconnect_started_ = true;
        disconnected_by_script_ = false;
        latest_.reset();
        start(now_ms);
        return false;
      }
      if (connected && latest_) {
        reconnect_started_ = false;
        return true;
      }
      return false;
  }
  return false;
}

void Bot::stop(std::uint64_t now_ms) {
  if (endpoint_ && endpoint_->state() == protocol::ClientState::connected)
    endpoint_->disconnect(now_ms, options_.probe ? protocol::kProbeByeReason : "done");
  finished_ = true;
}

nlohmann::ordered_json Bot::report() const {
  nlohmann::ordered_json r;
  r["name"] = options_.name;
  r["player_id"] = player_id_;
  r["token"] = token_;
  r["state"] = endpoint_ ? protocol::to_string(endpoint_->state()) : "idle";
  r["snapshots_received"] = snapshots_;
  const std::uint64_t expected = snapshots_ ? (last_tick_ - first_tick_) / ticks_per_snapshot_ + 1 : 0;
  r["snapshots_lost"] = expected > snapshots_ ? expected - snapshots_ : 0;
  r["rtt_p50_ms"] = percentile(rtt_samples_, 0.5);
  r["rtt_p99_ms"] = percentile(rtt_samples_, 0.99);
  const auto* p = me();
  r["coins"] = p ? p->coins : 0;
  r["lives"] = p ? p->lives : 0;
  r["level"] = latest_ ? latest_->level : 0;
  r["phase"] = latest_ ? phase_name(latest_->phase) : "none";
  r["purchases"] = purchases_ok_;
  r["purchase_events"] = purchase_events_;
  r["coins_earned_by_events"] = earned_;
  r["coins_spent_by_events"] = spent_;
  r["prices"] = p ? nlohmann::ordered_json(p->prices) : nlohmann::ordered_json::array();
  r["purchases_refused"] = purchases_refused_;
  r["bought"] = bought_;
  r["errors"] = errors_;
  r["ok"] = failure_.empty();
  return r;
}

}  // namespace fts::bot
