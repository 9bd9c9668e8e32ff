#include "bot/bot.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

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

}  // namespace

const char* phase_name(protocol::Phase p) {
  switch (p) {
    case protocol::Phase::lobby: return "lobby";
    case protocol::Phase::play: return "play";
    case protocol::Phase::shop: return "shop";
    case protocol::Phase::over: return "over";
  }
  return "?";
}

protocol::InputFrame Wander::input(std::uint32_t tick, sim::Rng& rng) {
  if (tick >= until_tick_) {
    frame_.move_x = static_cast<std::int8_t>(rng.uniform_int(-1, 1));
    frame_.move_y = static_cast<std::int8_t>(rng.uniform_int(-1, 1));
    until_tick_ = tick + static_cast<std::uint64_t>(rng.uniform_int(20, 80));
  }
  return frame_;
}

std::optional<Behavior> parse_behavior(const std::string& s) {
  if (s == "idle") return Behavior::idle;
  if (s == "wander") return Behavior::wander;
  if (s == "hunter") return Behavior::hunter;
  if (s == "shopper") return Behavior::shopper;
  return std::nullopt;
}

namespace {

protocol::ClientConfig connection_config(const BotOptions& o) {
  protocol::ClientConfig c;
  c.encoding = o.encoding;
  c.name = o.name;
  c.token = o.token;
  if (o.protocol_version) c.version = o.protocol_version;
  c.join = o.join;
  c.room = o.room;
  c.identity = o.identity;
  return c;
}

}  // namespace

// A bot (not a probe) resumes a lost connection with its token, like the client does.
Bot::Bot(BotOptions options)
    : options_(std::move(options)), conn_(connection_config(options_), /*resume_when_lost=*/!options_.probe),
      rng_(options_.seed), net_(options_.predict, [&] {
        client::PredictionTuning t;
        t.others = !options_.predict_own_only;
        t.remote = options_.predict_remote;
        return t;
      }()) {}

void Bot::start(std::uint64_t now_ms) { conn_.connect(now_ms); }

void Bot::receive(std::span<const std::uint8_t> bytes, std::uint64_t now_ms) { conn_.endpoint().receive(bytes, now_ms); }

std::vector<std::vector<std::uint8_t>> Bot::take_datagrams() { return conn_.endpoint().take_datagrams(); }

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
  if (name == "purchases") return static_cast<double>(tally_.purchases_ok());
  return NAN;
}

namespace {

// FNV-1a over what a snapshot says of the world (balls and players), not its events.
std::string snapshot_digest(const protocol::Snapshot& s) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  auto mix = [&](double v) {
    const auto q = static_cast<std::int64_t>(v * 16.0);
    for (int i = 0; i < 8; ++i) h = (h ^ static_cast<std::uint8_t>(q >> (8 * i))) * 0x100000001b3ull;
  };
  mix(s.tick);
  mix(static_cast<double>(s.phase));
  mix(s.level);
  for (const auto& b : s.balls) {
    mix(b.id), mix(b.x), mix(b.y), mix(b.vx), mix(b.vy), mix(b.radius), mix(b.owner);
  }
  for (const auto& p : s.players) {
    mix(p.id), mix(static_cast<double>(p.coins)), mix(p.lives), mix(p.mass), mix(p.alive ? 1 : 0);
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

// A sample kept for a percentile (the newest 100 000).
void keep_sample(std::vector<double>& v, double x) {
  if (v.size() >= 100000) v.erase(v.begin(), v.begin() + 50000);
  v.push_back(x);
}

}  // namespace

std::string Bot::room() const {
  const auto& w = conn_.endpoint().welcome();
  return w ? w->room : std::string();
}

void Bot::on_snapshot(const protocol::Snapshot& s) {
  tally_.on_snapshot(s);
  if (options_.predict) {
    const auto t0 = std::chrono::steady_clock::now();
    net_.on_snapshot(s, player_id_, now_ms_);
    keep_sample(predict_snapshot_us_, std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
  }
  digests_.emplace_back(s.tick, snapshot_digest(s));
  while (digests_.size() > 200) digests_.pop_front();
  // Each event once, by its seq (snapshots repeat them; PROTOCOL.md 8.4).
  for (const auto& e : s.events) {
    if (e.seq <= last_event_seq_) continue;
    last_event_seq_ = e.seq;
    new_events_.push_back(event_name(e.kind));
    tally_.on_event(e, player_id_);
  }
  if (s.phase != last_phase_) {
    sent_ready_for_phase_ = false;
    last_phase_ = s.phase;
  }
  latest_ = s;
}

void Bot::send_command(protocol::CommandOp op, char item, std::uint64_t now_ms) {
  pending_rid_ = conn_.endpoint().send_command(op, item, now_ms);
  if (pending_rid_ != 0) ++commands_sent_;
  pending_op_ = op;
  pending_item_ = item;
}

protocol::InputFrame Bot::behave() {
  protocol::InputFrame f;
  if (!latest_ || latest_->phase != protocol::Phase::play) return f;
  const auto* p = me();
  if (!p || !p->alive) return f;
  const bool hunting = script_.hunting || (options_.script.empty() &&
                                           (options_.behavior == Behavior::hunter || options_.behavior == Behavior::shopper));
  if (options_.script.empty() && options_.behavior == Behavior::wander) {
    return wander_.input(latest_->tick, rng_);
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
  if (const auto& w = conn_.endpoint().welcome()) {
    sight.arena_width_u = w->match.arena_width_u;
    sight.arena_height_u = w->match.arena_height_u;
  }
  const sim::PlayerInput in = sim::bot_play_input(sight);
  f.move_x = in.move_x;
  f.move_y = in.move_y;
  f.fire = in.fire;
  return f;
}

void Bot::update(std::uint64_t now_ms) {
  now_ms_ = now_ms;
  if (conn_.attempt() == 0 || finished_) return;
  conn_.update(now_ms);
  if (conn_.gone()) return fail("connection lost: no answer within the reconnect window");
  if (conn_.attempt() != seen_attempt_) {
    // A new session: a command in flight on the old one may or may not have been applied
    // (its result died with that session); the snapshots tell, so stop waiting for it.
    seen_attempt_ = conn_.attempt();
    pending_rid_ = 0;
  }
  switch (conn_.endpoint().state()) {
    case protocol::ClientState::refused: {
      const auto& e = conn_.endpoint().error();
      // "expect room refused CODE" as the step now: the refusal is the success.
      if (script_.pc < options_.script.size()) {
        const Step& s = options_.script[script_.pc];
        if (s.op == Step::Op::expect_room && s.word == "refused" && e && e->code == s.cmp) {
          refused_as_expected_ = e->code;
          finished_ = true;
          return;
        }
      }
      fail("refused by the server: " + (e ? e->code + ": " + e->message : std::string("no reason")));
      return;
    }
    case protocol::ClientState::timed_out:
      fail(options_.probe ? "no answer from the server (timed out)" : "connection timed out");
      return;
    case protocol::ClientState::disconnected:
      if (!script_.disconnected && !conn_.resuming()) {
        const auto& e = conn_.endpoint().error();
        fail("disconnected by the server" + (e ? ": " + e->code + ": " + e->message : std::string()));
        return;
      }
      break;
    default: break;
  }
  if (const auto& w = conn_.endpoint().welcome()) {
    if (player_id_ == 0 || w->player_id != 0) player_id_ = w->player_id;
    ticks_per_snapshot_ = std::max<std::uint32_t>(1, w->tick_rate_hz() / std::max<std::uint32_t>(1, w->snapshot_rate_hz));
    if (options_.predict && seen_welcome_ != conn_.attempt()) {
      seen_welcome_ = conn_.attempt();
      net_.on_welcome(*w);
    }
  }
  for (auto& r : conn_.endpoint().take_results()) {
    if (r.command_rid == pending_rid_) {
      pending_rid_ = 0;
      ++commands_answered_;
      if (pending_op_ == protocol::CommandOp::buy) tally_.on_purchase_result(r.ok, pending_item_);
    }
    last_result_ = r;
  }
  for (auto& s : conn_.endpoint().take_snapshots()) on_snapshot(s);
  if (conn_.state() == protocol::ClientState::connected) tally_.sample_rtt(conn_.endpoint().stats().rtt_ms, now_ms);
  if (options_.probe) {
    if (tally_.snapshots() > 0) finished_ = true;
    return;
  }
  if (!options_.script.empty()) {
    run_script(now_ms);
    new_events_.clear();
    if (finished_) return;
  } else if (latest_ && pending_rid_ == 0 && conn_.endpoint().state() == protocol::ClientState::connected) {
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
  const std::uint64_t tick_ms = conn_.endpoint().welcome() ? 1000 / std::max<std::uint32_t>(1, conn_.endpoint().welcome()->tick_rate_hz()) : 10;
  if (conn_.endpoint().state() == protocol::ClientState::connected && latest_ && now_ms >= last_input_ms_ + tick_ms) {
    last_input_ms_ = now_ms;
    protocol::InputFrame f = options_.script.empty() || script_.hunting ? behave() : script_.hold;
    if (script_.fire_once) {
      f.fire = true;
      script_.fire_once = false;
    }
    // --predict, as fts-client: the frame names the tick it acts at, the prediction takes
    // what went out, and the ball is predicted as the client would draw it (its CPU counts).
    if (net_.predicting()) f.tick = net_.stamp(net_.own_tick(now_ms, conn_.endpoint().stats().rtt_ms));
    if (conn_.endpoint().hold_input(f, now_ms) != 0) net_.sent(f);  // on change, with a keep-alive (lean uplink)
    if (net_.predicting()) {
      const auto t0 = std::chrono::steady_clock::now();
      (void)net_.own_ball(now_ms);
      keep_sample(predict_frame_us_, std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    }
  }
}

void Bot::stop(std::uint64_t now_ms) {
  if (conn_.state() == protocol::ClientState::connected)
    conn_.leave(now_ms, options_.probe ? protocol::kProbeByeReason : "done");
  finished_ = true;
}

nlohmann::ordered_json Bot::report() const {
  nlohmann::ordered_json r;
  r["name"] = options_.name;
  r["player_id"] = player_id_;
  r["token"] = conn_.token();
  r["state"] = protocol::to_string(conn_.state());
  r["snapshots_received"] = tally_.snapshots();
  r["snapshots_lost"] = tally_.snapshots_lost(ticks_per_snapshot_);
  r["rtt_p50_ms"] = tally_.rtt_percentile_ms(0.5);
  r["rtt_p99_ms"] = tally_.rtt_percentile_ms(0.99);
  const auto* p = me();
  r["coins"] = p ? p->coins : 0;
  r["lives"] = p ? p->lives : 0;
  r["level"] = latest_ ? latest_->level : 0;
  r["phase"] = latest_ ? phase_name(latest_->phase) : "none";
  r["purchases"] = tally_.purchases_ok();
  r["purchase_events"] = tally_.purchase_events();
  r["coins_earned_by_events"] = tally_.coins_earned();
  r["coins_spent_by_events"] = tally_.coins_spent();
  r["prices"] = p ? nlohmann::ordered_json(p->prices) : nlohmann::ordered_json::array();
  r["purchases_refused"] = tally_.purchases_refused();
  r["bought"] = tally_.bought();
  r["commands_sent"] = commands_sent_;
  r["commands_answered"] = commands_answered_;
  r["command_pending"] = pending_rid_ != 0;
  r["room"] = room();
  r["moves"] = conn_.moves();
  if (conn_.moves() != 0) r["moved_to"] = conn_.moved_to();
  if (const auto& w = conn_.endpoint().welcome()) r["spectator"] = w->spectator;
  if (!refused_as_expected_.empty()) r["refused"] = refused_as_expected_;
  r["snapshot_digests"] = nlohmann::ordered_json::object();
  for (const auto& [tick, digest] : digests_) r["snapshot_digests"][std::to_string(tick)] = digest;
  if (options_.predict) {
    const auto& p = net_.prediction();
    r["prediction"] = {{"corrections", p.corrections}, {"snaps", p.snaps}, {"contact_corrections", p.contact_corrections},
                       {"correction_p50_radii", client::percentile(p.all_sizes_radii, 50)},
                       {"correction_p99_radii", client::percentile(p.all_sizes_radii, 99)},
                       {"free_corrections", p.free_sizes_radii.size()},
                       {"free_correction_p50_radii", client::percentile(p.free_sizes_radii, 50)},
                       {"free_correction_p99_radii", client::percentile(p.free_sizes_radii, 99)},
                       {"contact_correction_p50_radii", client::percentile(p.contact_sizes_radii, 50)},
                       {"contact_correction_p99_radii", client::percentile(p.contact_sizes_radii, 99)},
                       {"others", !options_.predict_own_only},
                       {"balls_per_tick_stepped", p.ticks_stepped ? static_cast<double>(p.balls_stepped) / static_cast<double>(p.ticks_stepped) : 0.0},
                       {"frame_us_p50", client::percentile(predict_frame_us_, 50)},
                       {"frame_us_p99", client::percentile(predict_frame_us_, 99)},
                       {"snapshot_us_p50", client::percentile(predict_snapshot_us_, 50)},
                       {"snapshot_us_p99", client::percentile(predict_snapshot_us_, 99)},
                       {"lead_ticks", net_.lead_ticks()}, {"jitter_ms", net_.jitter_ms()}};
  }
  r["errors"] = errors_;
  r["ok"] = failure_.empty();
  return r;
}

}  // namespace fts::bot
