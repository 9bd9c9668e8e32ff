#include "app/game_host.hpp"

#include <algorithm>
#include <memory>

#include "app/log.hpp"
#include "app/snapshot_build.hpp"
#include "fts/sim/match_view.hpp"

namespace fts::server {
namespace {

constexpr std::size_t kRecentEvents = 48;

std::string refusal_code(sim::Refusal r) {
  switch (r) {
    case sim::Refusal::none: return "ok";
    case sim::Refusal::not_enough_coins: return "coins";
    case sim::Refusal::already_owned: return "owned";
    case sim::Refusal::wrong_phase: return "phase";
    case sim::Refusal::unknown_item: return "item";
    case sim::Refusal::no_player: return "dead";
  }
  return "error";
}

// The sentence of a command's result.
std::string result_message(const sim::CommandResult& r) {
  if (r.kind != sim::CommandKind::buy) {
    if (r.ok()) return "done";
    return r.code == sim::Refusal::no_player ? "not in the match" : "not now (wrong phase)";
  }
  if (r.code == sim::Refusal::no_player) return "not in the match";
  const std::string item(sim::to_string(r.item));
  if (r.ok()) return item + " bought for " + std::to_string(r.price) + " coins, " + std::to_string(r.coins_after) + " left";
  return item + " not bought: " + std::string(sim::to_string(r.code));
}

}  // namespace

protocol::ServerConfig make_endpoint_config(const Options& o, const sim::MatchConfig& cfg,
                                            const protocol::ServerKey& key) {
  protocol::ServerConfig c;
  c.key = key;
  c.max_players = o.max_players;
  c.timeout_ms = o.timeout_ms;
  c.reconnect_window_ms = o.reconnect_window_ms;
  c.max_sessions_per_address = o.max_per_address;
  c.idle_timeout_ms = o.idle_timeout_ms;
  // A host may send what its sessions may send together.
  c.address_datagrams_per_s = c.address_datagram_burst = c.session_datagrams_per_s * o.max_per_address;
  c.snapshot_max_base_age_ticks = o.tick_rate_hz;  // one second
  c.settings.tick_rate_hz = o.tick_rate_hz;
  c.settings.snapshot_rate_hz = o.snapshot_rate_hz;
  c.settings.arena_width_u = cfg.arena_width_u;
  c.settings.arena_height_u = cfg.arena_height_u;
  c.settings.max_players = o.max_players;
  c.settings.timeout_ms = o.timeout_ms;
  c.settings.reconnect_window_ms = o.reconnect_window_ms;
  c.settings.shop = sim::shop_terms(cfg);
  return c;
}

GameHost::GameHost(const Options& options, const sim::MatchConfig& config, const protocol::ServerKey& key)
    : options_(options),
      match_(sim::make_match(config, options.seed)),
      endpoint_(make_endpoint_config(options, config, key)) {
  ticks_per_snapshot_ = std::max<std::uint32_t>(1, options.tick_rate_hz / std::max<std::uint32_t>(1, options.snapshot_rate_hz));
}

void GameHost::record_to(std::ostream& out, const std::string& version) {
  recorder_ = std::make_unique<host::RecordWriter>(out, options_.seed, match_.cfg, version);
}

std::uint32_t GameHost::wire_event_count(std::int64_t tick, const sim::TickOutput& out) {
  std::vector<protocol::Event> wire;
  append_wire_events(tick + 1, out.events, wire);
  return static_cast<std::uint32_t>(wire.size());
}

void GameHost::resume_from(const host::ResumedRoom& room, std::uint64_t now_ms) {
  match_ = room.state;
  event_seq_ = room.event_seq;
  last_phase_ = match_.phase;
  endpoint_.set_server_tick(static_cast<std::uint32_t>(match_.tick));
  for (const auto& s : room.sessions) {
    // Each comes back as "disconnected" in the next tick's events: the match marks it away.
    if (!endpoint_.restore_session({s.player, s.name, s.verifier, s.quit}, now_ms))
      log_record(spdlog::level::warn, "resume_session_refused", {{"player", s.player}, {"name", s.name}});
  }
}

void GameHost::journal_to(host::JournalConfig config) {
  std::vector<host::JournalSession> sessions;
  for (const auto& s : endpoint_.sessions())
    sessions.push_back({s.player_id, s.name, endpoint_.session_verifier(s.player_id), !s.connected});
  journal_ = std::make_unique<host::JournalWriter>(std::move(config), match_.cfg, match_, event_seq_, std::move(sessions));
}

void GameHost::journal_session(const protocol::ServerEvent& e) {
  if (!journal_) return;
  using K = protocol::ServerEvent::Kind;
  if (e.kind == K::released) return journal_->released(match_.tick, e.player_id);
  const bool quit = e.kind == K::disconnected && e.quit;
  journal_->session(match_.tick, {e.player_id, e.name, endpoint_.session_verifier(e.player_id), quit});
}

// Every 10 s: a journal that dropped records or failed says so (once per change).
void GameHost::watch_journal() {
  const auto st = journal_->stats();
  if (st.dropped != journal_dropped_logged_) {
    log_record(spdlog::level::warn, "journal_dropped",
               {{"records", st.dropped - journal_dropped_logged_}, {"total", st.dropped}, {"durable_tick", st.durable_tick}});
    journal_dropped_logged_ = st.dropped;
  }
  if (!st.error.empty() && !journal_error_logged_) {
    log_record(spdlog::level::err, "journal_failed", {{"error", st.error}, {"durable_tick", st.durable_tick}});
    journal_error_logged_ = true;
  }
}

void GameHost::receive(const std::string& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms) {
  ++stats_.datagrams_in;
  stats_.bytes_in += bytes.size();
  ++stats_.totals.datagrams_in;
  stats_.totals.bytes_in += bytes.size();
  endpoint_.receive(from, bytes, now_ms);
}

std::vector<protocol::Outgoing> GameHost::take_datagrams() {
  auto out = endpoint_.take_datagrams();
  for (const auto& d : out) {
    ++stats_.datagrams_out;
    stats_.bytes_out += d.bytes.size();
    ++stats_.totals.datagrams_out;
    stats_.totals.bytes_out += d.bytes.size();
  }
  return out;
}

sim::TickInputs GameHost::gather(std::uint64_t now_ms) {
  // Nobody idles while the players cannot act: lobby, shop countdown, game over.
  endpoint_.set_idle_paused(match_.phase != sim::Phase::playing);
  endpoint_.update(now_ms);
  sim::TickInputs in;
  for (const auto& e : endpoint_.take_events()) {
    using K = protocol::ServerEvent::Kind;
    journal_session(e);
    switch (e.kind) {
      case K::connected:
        if (draining_) {  // a draining server takes nobody new (fleet: SIGTERM or drain)
          endpoint_.kick(e.player_id, "draining", "this server is shutting down; join another", now_ms);
          log_record(spdlog::level::info, "join_refused", {{"player", e.player_id}, {"reason", "draining"}});
          break;
        }
        in.joins.push_back({e.player_id, e.name});
        log_record(spdlog::level::info, "connect", {{"player", e.player_id}, {"name", e.name}});
        break;
      case K::reconnected:
        held_.erase(e.player_id);  // the new session numbers its inputs from 1 again
        in.back.push_back(e.player_id);
        log_record(spdlog::level::info, "reconnect", {{"player", e.player_id}, {"name", e.name}});
        break;
      case K::disconnected:
        held_.erase(e.player_id);  // a gone client stops pushing
        // A quit takes the ball off at once; a lost connection leaves it (for a resume).
        (e.quit ? in.quit : in.away).push_back(e.player_id);
        log_record(spdlog::level::info, "disconnect", {{"player", e.player_id}, {"reason", e.reason}});
        break;
      case K::released:
        held_.erase(e.player_id);
        in.leaves.push_back(e.player_id);
        log_record(spdlog::level::info, "leave", {{"player", e.player_id}, {"reason", e.reason}});
        break;
    }
  }
  // Inputs arrive in (player, seq) order; the newest frame holds until a newer one, or
  // until input_expiry_ms pass without one: a crashed client's held key goes neutral
  // (PROTOCOL.md 4.5). The recording holds what the match was given, so a replay
  // repeats the expiry exactly.
  for (const auto& pi : endpoint_.take_inputs()) {
    Held& h = held_[pi.player_id];
    if (pi.frame.seq >= h.frame.seq) h.frame = pi.frame;
    h.fire = h.fire || pi.frame.fire;
    h.received_ms = now_ms;
  }
  std::map<std::uint32_t, sim::PlayerTick> ticks;
  for (auto& [id, h] : held_) {
    sim::PlayerTick& t = ticks[id];
    t.player = id;
    const bool expired = now_ms - h.received_ms > options_.input_expiry_ms;
    t.input.move_x = expired ? 0 : static_cast<std::int8_t>(std::clamp<int>(h.frame.move_x, -1, 1));
    t.input.move_y = expired ? 0 : static_cast<std::int8_t>(std::clamp<int>(h.frame.move_y, -1, 1));
    t.input.fire = h.fire;
    h.fire = false;
  }
  for (const auto& pc : endpoint_.take_commands()) {
    sim::PlayerTick& t = ticks[pc.player_id];
    t.player = pc.player_id;
    switch (pc.command.op) {
      case protocol::CommandOp::buy:
        t.commands.push_back({sim::CommandKind::buy, pc.command.item ? std::string(1, pc.command.item) : std::string(),
                              pc.command.rid});
        break;
      case protocol::CommandOp::ready: t.commands.push_back({sim::CommandKind::ready, {}, pc.command.rid}); break;
      case protocol::CommandOp::play_again:
        t.commands.push_back({sim::CommandKind::play_again, {}, pc.command.rid});
        break;
      case protocol::CommandOp::chat: relay_chat(pc, now_ms); break;
      case protocol::CommandOp::unknown:  // consumed and answered here: the match has no such command
        endpoint_.send_result(pc.player_id, pc.command.rid, false, "op",
                              "unknown command; this server knows buy, ready and again", now_ms);
        break;
    }
  }
  for (auto& [id, t] : ticks) {
    // Inputs of players that have not joined the match (yet) have nothing to apply; their
    // commands still go to the step, which answers them.
    const bool joining = std::any_of(in.joins.begin(), in.joins.end(), [&](const auto& j) { return j.player == id; });
    if (sim::find_player(match_, id) || joining || !t.commands.empty()) in.players.push_back(std::move(t));
  }
  return in;
}

void GameHost::relay_chat(const protocol::PlayerCommand& pc, std::uint64_t now_ms) {
  const ChatVerdict v = chat_.accept(pc.player_id, pc.command.text, now_ms);
  if (!v.ok) {
    endpoint_.send_result(pc.player_id, pc.command.rid, false, v.code,
                          v.code == "rate" ? "too many chat lines: wait a moment" : "nothing to say", now_ms);
    return;
  }
  endpoint_.send_result(pc.player_id, pc.command.rid, true, "ok", "", now_ms);
  const sim::Player* p = sim::find_player(match_, sim::PlayerId{pc.player_id});
  protocol::Chat line;
  line.from = pc.player_id;
  line.name = p != nullptr ? p->name : "player " + std::to_string(pc.player_id);
  line.text = v.text;
  for (const std::uint32_t to : endpoint_.connected_players()) endpoint_.send_chat(to, line, now_ms);
  log_record(spdlog::level::info, "chat", {{"player", pc.player_id}, {"chars", v.text.size()}});
}

void GameHost::answer(const std::vector<sim::CommandResult>& results, std::uint64_t now_ms) {
  for (const sim::CommandResult& r : results)
    endpoint_.send_result(r.player.value, r.tag, r.ok(), refusal_code(r.code), result_message(r), now_ms);
}

void GameHost::log_events(const std::vector<sim::Event>& events, std::uint64_t now_ms) {
  for (const auto& event : events) {
    std::visit(
        sim::Overloaded{
            [&](const sim::JoinRefused& e) {
              log_record(spdlog::level::warn, "join_refused", {{"player", e.player}, {"reason", e.reason}});
              endpoint_.kick(e.player.value, "refused", "the match refused the join: " + e.reason, now_ms);
            },
            [&](const sim::LevelStarted& e) {
              log_record(spdlog::level::info, e.restart ? "level_restart" : "level_start", {{"level", e.level}});
            },
            [&](const sim::LevelComplete& e) { log_record(spdlog::level::info, "level_complete", {{"level", e.level}}); },
            [&](const sim::Purchased& e) {
              ++(e.ok ? stats_.totals.purchases : stats_.totals.purchases_refused);
              log_record(e.ok ? spdlog::level::info : refused_log_.level(now_ms), "purchase",
                         {{"player", e.player}, {"item", std::string(sim::to_string(e.item))}, {"ok", e.ok},
                          {"reason", std::string(sim::to_string(e.reason))}, {"price", e.price}, {"coins", e.coins_after}, {"tick", match_.tick}});
            },
            [&](const sim::GameOver& e) { log_record(spdlog::level::info, "game_over", {{"level", e.level}}); },
            [&](const sim::EnemyDefeated& e) {
              log_record(spdlog::level::debug, "enemy_defeated", {{"enemy", e.enemy}, {"player", e.player}, {"coins", e.coins}, {"tick", match_.tick}});
            },
            [&](const sim::PlayerFell& e) {
              log_record(spdlog::level::debug, "player_fell", {{"player", e.player}, {"lives", e.lives_left}});
            },
            [&](const sim::InterestPaid& e) {
              log_record(spdlog::level::debug, "interest", {{"player", e.player}, {"coins", e.coins}, {"tick", match_.tick}});
            },
            [](const auto&) {},  // the rest is not logged
        },
        event);
  }
  refused_log_.flush(now_ms);
}

void GameHost::tick(std::uint64_t now_ms) {
  if (const auto stalled = endpoint_.stalled_ms(); stalled != stalled_logged_ms_) {
    log_record(spdlog::level::warn, "stall", {{"ms", stalled - stalled_logged_ms_}, {"total_ms", stalled}});
    stalled_logged_ms_ = stalled;
  }
  const sim::TickInputs in = gather(now_ms);
  if (recorder_) recorder_->inputs(match_.tick, in);
  if (journal_) journal_->inputs(match_.tick, in);
  const sim::TickOutput stepped = sim::step(match_, in);
  const std::vector<sim::Event>& events = stepped.events;
  if (recorder_) recorder_->stepped(match_);
  answer(stepped.results, now_ms);
  log_events(events, now_ms);

  std::vector<protocol::Event> wire;
  append_wire_events(match_.tick, events, wire);
  for (auto& w : wire) {
    w.seq = ++event_seq_;
    recent_.push_back(w);
  }
  while (recent_.size() > kRecentEvents) recent_.pop_front();
  if (journal_) {
    journal_->stepped(match_, event_seq_);
    if (match_.tick % 1000 == 0) watch_journal();
  }

  endpoint_.set_server_tick(static_cast<std::uint32_t>(match_.tick));
  if (match_.tick % ticks_per_snapshot_ == 0) send_snapshots(now_ms);
}

void GameHost::send_snapshots(std::uint64_t now_ms) {
  const auto players = endpoint_.connected_players();
  if (players.empty()) return;
  // Quantized once per tick; each client gets only its delta against that.
  const auto snap = std::make_shared<const protocol::Snapshot>(
      protocol::quantize(build_snapshot(sim::make_view(match_), recent_)));
  for (auto id : players) endpoint_.send_snapshot(id, snap, now_ms);
}

void GameHost::shutdown(std::uint64_t now_ms) {
  endpoint_.shutdown(now_ms);
  if (recorder_) recorder_->flush();
  // The shutdown's releases are not journaled: a clean stop resumes like a crash.
  if (journal_) journal_->flush();
}

}  // namespace fts::server
