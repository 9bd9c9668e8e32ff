#include "app/room.hpp"

#include <algorithm>
#include <memory>

#include "fts/sim/match_view.hpp"

namespace fts::server {
namespace {

// The sentence of a command's result: the refusal table's, with the item named where
// there is one (an unknown item has no name of its own: r.item is only a default then).
std::string result_message(const sim::CommandResult& r) {
  const std::string sentence(sim::refusal_info(r.code).sentence);
  if (r.kind != sim::CommandKind::buy || r.code == sim::Refusal::no_player || r.code == sim::Refusal::unknown_item)
    return sentence;
  const std::string item(sim::to_string(r.item));
  if (r.ok()) return item + " bought for " + std::to_string(r.price) + " coins, " + std::to_string(r.coins_after) + " left";
  return item + " not bought: " + sentence;
}

}  // namespace

protocol::ResultCode refusal_code(sim::Refusal r) {
  switch (r) {
    case sim::Refusal::none: return protocol::ResultCode::ok;
    case sim::Refusal::not_enough_coins: return protocol::ResultCode::coins;
    case sim::Refusal::already_owned: return protocol::ResultCode::owned;
    case sim::Refusal::wrong_phase: return protocol::ResultCode::phase;
    case sim::Refusal::unknown_item: return protocol::ResultCode::item;
    case sim::Refusal::no_player: return protocol::ResultCode::dead;
  }
  return protocol::ResultCode::phase;
}

Room::Room(std::uint32_t id, std::string code, bool is_private, std::uint64_t seed, const Options& options,
           const sim::MatchConfig& config)
    : id_(id),
      code_(std::move(code)),
      private_(is_private),
      seed_(seed),
      input_expiry_ms_(options.input_expiry_ms),
      stepper_(config, seed) {
  ticks_per_snapshot_ = std::max<std::uint32_t>(1, options.tick_rate_hz / std::max<std::uint32_t>(1, options.snapshot_rate_hz));
}

bool Room::record_to(const std::string& dir, const std::string& version) {
  std::error_code ec;
  for (const auto& [n, path] : store::list_segments(dir)) std::filesystem::remove(path, ec);  // a record starts afresh
  store::JournalConfig c;
  c.dir = dir;
  c.room = code_;
  c.room_id = id_;
  c.is_private = private_;
  c.version = version;
  c.seed = seed_;
  c.keep_all = true;
  recorder_ = std::make_unique<store::JournalWriter>(std::move(c), stepper_.match().cfg, stepper_.match(),
                                                    stepper_.event_seq(), std::vector<store::JournalSession>{});
  if (!recorder_->stats().error.empty()) {
    recorder_.reset();
    return false;
  }
  record_path_ = dir;
  return true;
}

std::unique_ptr<store::JournalWriter> Room::finish_record() {
  if (!recorder_) return nullptr;
  recorder_->hash_now(stepper_.match(), stepper_.event_seq());
  recorder_->finish();
  return std::move(recorder_);
}

std::string Room::shown_name(std::uint32_t player_id, const std::string& fallback) const {
  const sim::Player* p = sim::find_player(stepper_.match(), sim::PlayerId{player_id});
  return p ? p->name : fallback;
}

void Room::on_event(const protocol::ServerEvent& e, const protocol::ServerEndpoint& endpoint) {
  using K = protocol::ServerEvent::Kind;
  journal_session(e, endpoint);
  const std::string_view who = e.spectator ? "spectator" : "player";
  switch (e.kind) {
    case K::connected:
      if (!e.spectator) pending_.joins.push_back({e.player_id, e.name});
      if (profiles_ && !e.spectator) careers_.identify(e.player_id, e.identity, e.name);
      log_record(spdlog::level::info, "connect", {{who, e.player_id}, {"name", e.name}, {"room", id_}});
      break;
    case K::reconnected:
      held_.erase(e.player_id);  // the new session numbers its inputs from 1 again
      if (!e.spectator) pending_.back.push_back(e.player_id);
      if (profiles_ && !e.spectator) careers_.identify(e.player_id, e.identity, shown_name(e.player_id, e.name));
      log_record(spdlog::level::info, "reconnect", {{who, e.player_id}, {"name", e.name}, {"room", id_}});
      break;
    case K::disconnected:
      held_.erase(e.player_id);  // a gone client stops pushing
      // A quit takes the ball off at once; a lost connection leaves it (for a resume).
      if (!e.spectator) (e.quit ? pending_.quit : pending_.away).push_back(e.player_id);
      log_record(spdlog::level::info, "disconnect",
                 {{who, e.player_id}, {"reason", e.reason}, {"room", id_}, {"name", shown_name(e.player_id, e.name)}});
      break;
    case K::released:
      held_.erase(e.player_id);
      if (profiles_) {
        if (auto r = careers_.released(e.player_id, stepper_.match().cfg.tick_rate_hz, unix_s_())) push_result(*r);
      }
      journaled_.erase(e.player_id);
      if (!e.spectator) pending_.leaves.push_back(e.player_id);
      log_record(spdlog::level::info, "leave",
                 {{who, e.player_id}, {"reason", e.reason}, {"room", id_}, {"name", shown_name(e.player_id, e.name)}});
      break;
  }
}

// Inputs arrive in (player, seq) order; the newest frame holds until a newer one, or
// until input_expiry_ms pass without one: a crashed client's held key goes neutral
// (PROTOCOL.md 4.5). The recording holds what the match was given, so a replay repeats
// the expiry exactly.
//
// A frame that names a later tick (a predicting client, PROTOCOL.md 4.5) waits for it in a
// bounded per-player buffer, so that the server applies it at the tick the client's
// prediction did; a frame for a tick already stepped is applied at once (late).
void Room::on_input(const protocol::PlayerInput& pi, std::uint64_t now_ms) {
  Held& h = held_[pi.player_id];
  const protocol::InputFrame& f = pi.frame;
  const std::int64_t now_tick = stepper_.match().tick;
  if (f.tick == 0) {
    ++timing_.untimed;
  } else if (static_cast<std::int64_t>(f.tick) <= now_tick) {
    ++timing_.late;
  } else if (static_cast<std::int64_t>(f.tick) - now_tick > max_lead_ticks(stepper_.match().cfg.tick_rate_hz)) {
    ++timing_.too_early;
  } else {
    if (h.early.size() >= kMaxEarlyFrames) {
      ++timing_.overflow;
      hold(h, h.early.front(), now_ms);
      h.early.pop_front();
    }
    h.early.push_back(f);
    return;
  }
  hold(h, f, now_ms);
}

void Room::hold(Held& h, const protocol::InputFrame& f, std::uint64_t now_ms) {
  if (f.seq >= h.frame.seq) h.frame = f;
  h.fire = h.fire || f.fire;
  h.received_ms = now_ms;
}

void Room::on_command(const protocol::PlayerCommand& pc, protocol::ServerEndpoint& endpoint, std::uint64_t now_ms) {
  sim::PlayerTick* t = nullptr;
  for (auto& p : pending_.players)
    if (p.player == pc.player_id) t = &p;
  if (!t) {
    pending_.players.emplace_back();
    t = &pending_.players.back();
    t->player = pc.player_id;
  }
  switch (pc.command.op) {
    case protocol::CommandOp::buy:
      t->commands.push_back({sim::CommandKind::buy, pc.command.item ? std::string(1, pc.command.item) : std::string(),
                             pc.command.rid});
      break;
    case protocol::CommandOp::ready: t->commands.push_back({sim::CommandKind::ready, {}, pc.command.rid}); break;
    case protocol::CommandOp::play_again:
      t->commands.push_back({sim::CommandKind::play_again, {}, pc.command.rid});
      break;
    case protocol::CommandOp::rooms:  // the host answers these
    case protocol::CommandOp::chat:
    case protocol::CommandOp::top:
    case protocol::CommandOp::forget:
    case protocol::CommandOp::unknown:  // consumed and answered here: the match has no such command
      endpoint.send_result(pc.player_id, pc.command.rid, protocol::ResultCode::op,
                           "unknown command; this server knows buy, ready, again, chat, rooms, top and forget", now_ms);
      break;
  }
}

sim::TickInputs Room::gather(std::uint64_t now_ms) {
  sim::TickInputs in = std::exchange(pending_, {});
  sim::IdMap<std::uint32_t, sim::PlayerTick> ticks;
  for (auto& t : in.players) ticks[t.player.value] = std::move(t);
  in.players.clear();
  for (auto& [id, h] : held_) {
    // Early frames whose tick has come are in force from this tick on.
    while (!h.early.empty() && static_cast<std::int64_t>(h.early.front().tick) <= stepper_.match().tick) {
      ++timing_.on_time;
      hold(h, h.early.front(), now_ms);
      h.early.pop_front();
    }
    sim::PlayerTick& t = ticks[id];
    t.player = id;
    const bool expired = now_ms - h.received_ms > input_expiry_ms_;
    t.input.move_x = expired ? 0 : static_cast<std::int8_t>(std::clamp<int>(h.frame.move_x, -1, 1));
    t.input.move_y = expired ? 0 : static_cast<std::int8_t>(std::clamp<int>(h.frame.move_y, -1, 1));
    t.input.fire = h.fire;
    h.fire = false;
  }
  for (auto& [player, t] : ticks) {
    const std::uint32_t id = player;  // a lambda cannot capture a binding before clang 16
    // Inputs of players that have not joined the match (yet) have nothing to apply; their
    // commands still go to the step, which answers them.
    const bool joining = std::any_of(in.joins.begin(), in.joins.end(), [&](const auto& j) { return j.player == id; });
    if (sim::find_player(stepper_.match(), id) || joining || !t.commands.empty()) in.players.push_back(std::move(t));
  }
  return in;
}

void Room::answer(const std::vector<sim::CommandResult>& results, protocol::ServerEndpoint& endpoint,
                  std::uint64_t now_ms) {
  for (const sim::CommandResult& r : results)
    endpoint.send_result(r.player.value, r.tag, refusal_code(r.code), result_message(r), now_ms);
}

void Room::log_events(const std::vector<sim::Event>& events, protocol::ServerEndpoint& endpoint, std::uint64_t now_ms) {
  for (const auto& event : events) {
    std::visit(
        sim::Overloaded{
            [&](const sim::JoinRefused& e) {
              const auto& why = sim::join_refusal_info(e.reason);
              log_record(spdlog::level::warn, "join_refused",
                         {{"player", e.player}, {"reason", std::string(why.name)}, {"room", id_}});
              endpoint.kick(e.player.value, protocol::ErrorCode::refused,
                            "the match refused the join: " + std::string(why.sentence), now_ms);
            },
            [&](const sim::LevelStarted& e) {
              log_record(spdlog::level::info, e.restart ? "level_restart" : "level_start", {{"level", e.level}, {"room", id_}});
            },
            [&](const sim::LevelComplete& e) {
              log_record(spdlog::level::info, "level_complete", {{"level", e.level}, {"room", id_}});
            },
            [&](const sim::Purchased& e) {
              if (totals_) ++(e.ok ? totals_->purchases : totals_->purchases_refused);
              log_record(e.ok ? spdlog::level::info : refused_log_.level(now_ms), "purchase",
                         {{"player", e.player}, {"item", std::string(sim::to_string(e.item))}, {"ok", e.ok},
                          {"reason", std::string(sim::to_string(e.reason))}, {"price", e.price}, {"coins", e.coins_after}, {"room", id_},
                          {"tick", stepper_.match().tick}});
            },
            [&](const sim::GameOver& e) { log_record(spdlog::level::info, "game_over", {{"level", e.level}, {"room", id_}}); },
            [&](const sim::EnemyDefeated& e) {
              log_record(spdlog::level::debug, "enemy_defeated",
                         {{"enemy", e.enemy}, {"player", e.player}, {"coins", e.coins}, {"room", id_}, {"tick", stepper_.match().tick}});
            },
            [&](const sim::PlayerFell& e) {
              log_record(spdlog::level::debug, "player_fell", {{"player", e.player}, {"lives", e.lives_left}, {"room", id_}});
            },
            [&](const sim::InterestPaid& e) {
              log_record(spdlog::level::debug, "interest",
                         {{"player", e.player}, {"coins", e.coins}, {"room", id_}, {"tick", stepper_.match().tick}});
            },
            [](const auto&) {},  // the rest is not logged
        },
        event);
  }
  refused_log_.flush(now_ms);
}

void Room::step(std::uint64_t now_ms) {
  const sim::TickInputs in = gather(now_ms);
  if (recorder_) recorder_->inputs(stepper_.match().tick, in);
  if (journal_) journal_->inputs(stepper_.match().tick, in);
  stepped_ = stepper_.step(in);
  if (recorder_) recorder_->stepped(stepper_.match(), stepper_.event_seq());
  if (journal_) journal_->stepped(stepper_.match(), stepper_.event_seq());
}

void Room::publish(protocol::ServerEndpoint& endpoint, std::uint64_t now_ms) {
  answer(stepped_.results, endpoint, now_ms);
  log_events(stepped_.events, endpoint, now_ms);
  if (profiles_) {
    std::vector<std::uint32_t> changed;
    for (const auto& r : careers_.step(stepper_.match(), stepped_.events, unix_s_(), &changed)) push_result(r);
    if (!changed.empty()) journal_careers(changed, endpoint);
  }
  if (journal_ && stepper_.match().tick % 100 == 0) watch_journal();
  endpoint.set_server_tick(id_, static_cast<std::uint32_t>(stepper_.match().tick));
}

void Room::send_snapshots(const protocol::RoomSessions& members, std::uint64_t now_ms, protocol::SendLane& lane) {
  for (const sim::Player& p : stepper_.match().players) members.set_watching(p.id.value, !p.in_match());
  // Rooms take turns (room 1 at multiples of ticks_per_snapshot_, room 2 a tick later...):
  // a host's snapshot work spreads over every tick instead of piling up on one in five.
  const auto turn = static_cast<std::int64_t>(id_ - 1);
  if ((stepper_.match().tick + turn) % ticks_per_snapshot_ != 0 || members.empty()) return;
  // Quantized once per tick; each client gets only its delta against that.
  const auto snap = std::make_shared<const protocol::Snapshot>(protocol::quantize(stepper_.snapshot()));
  members.send_snapshot(snap, now_ms, lane);
}

void Room::start_sync() {
  if (!journal_) return;
  journal_->checkpoint_now(stepper_.match(), stepper_.event_seq());
  journal_->request_flush();
}

bool Room::finish_sync() {
  if (!journal_) return false;
  journal_->flush();
  const auto st = journal_->stats();
  return !st.failing && st.dropped == 0 && st.error.empty();
}

void Room::seal() {
  if (recorder_) recorder_->hash_now(stepper_.match(), stepper_.event_seq());
  flush();
}

void Room::flush() {
  if (recorder_) recorder_->flush();
  // The shutdown's releases are not journaled: a clean stop resumes like a crash.
  if (journal_) journal_->flush();
}

void Room::resume_from(const store::ResumedRoom& room) { stepper_ = room::RoomStepper(room.state, room.event_seq); }

void Room::journal_to(store::JournalConfig config, const protocol::ServerEndpoint& endpoint) {
  std::vector<store::JournalSession> sessions;
  for (const auto& s : endpoint.sessions_of_room(id_))
    if (!s.spectator)
      sessions.push_back({s.player_id, s.name, endpoint.session_verifier(s.player_id), !s.connected, s.identity,
                          careers_.saved(s.player_id)});
  journal_ = std::make_unique<store::JournalWriter>(std::move(config), stepper_.match().cfg, stepper_.match(), stepper_.event_seq(),
                                                   std::move(sessions));
  watch_journal();  // a directory locked by another server: the room plays on without a journal, said once
}

std::unique_ptr<store::JournalWriter> Room::finish_journal() {
  if (journal_) journal_->finish();
  return std::move(journal_);
}

void Room::journal_session(const protocol::ServerEvent& e, const protocol::ServerEndpoint& endpoint) {
  if (!journal_ || e.spectator) return;
  using K = protocol::ServerEvent::Kind;
  if (e.kind == K::released) return journal_->released(stepper_.match().tick, e.player_id);
  const bool quit = e.kind == K::disconnected && e.quit;
  store::JournalSession s{e.player_id, e.name, endpoint.session_verifier(e.player_id), quit,
                         endpoint.session_identity(e.player_id), careers_.saved(e.player_id)};
  journaled_[e.player_id] = s;
  journal_->session(stepper_.match().tick, s);
}

// A player's match so far goes into the journal with its session (each change: a knock,
// a fall, a level, its end), so that a resumed room ends it under the same key.
void Room::journal_careers(const std::vector<std::uint32_t>& players, const protocol::ServerEndpoint& endpoint) {
  if (!journal_) return;
  for (std::uint32_t p : players) {
    auto it = journaled_.find(p);
    if (it == journaled_.end()) {
      store::JournalSession s{p, shown_name(p, ""), endpoint.session_verifier(p), false, endpoint.session_identity(p), ""};
      if (s.verifier.empty()) continue;
      it = journaled_.emplace(p, s).first;
    }
    const std::string saved = careers_.saved(p);
    if (saved == it->second.career) continue;
    it->second.career = saved;
    journal_->session(stepper_.match().tick, it->second);
  }
}

void Room::push_result(const profiles::MatchResult& r) {
  if (!profiles_) return;
  const bool ok = profiles_->push(r);
  log_record(ok ? spdlog::level::info : spdlog::level::warn, "match_result",
             {{"room", id_}, {"identity", r.fingerprint}, {"name", r.name}, {"level", r.level}, {"coins", r.coins},
              {"knocks", r.knocks}, {"lives_lost", r.lives_lost}, {"ending", profiles::to_string(r.ending)},
              {"key", r.key}, {"queued", ok}});
}

void Room::close_careers() {
  if (!profiles_) return;
  for (const auto& r : careers_.close(stepper_.match().cfg.tick_rate_hz, unix_s_())) push_result(r);
}

// Every second: a journal that dropped records says so (once per change); one that
// failed says so once when it stops and once when it goes on again.
void Room::watch_journal() {
  const auto st = journal_->stats();
  if (st.dropped != journal_dropped_logged_) {
    log_record(spdlog::level::warn, "journal_dropped",
               {{"records", st.dropped - journal_dropped_logged_}, {"total", st.dropped}, {"durable_tick", st.durable_tick},
                {"room", id_}});
    journal_dropped_logged_ = st.dropped;
  }
  if (st.failures != journal_failures_) {
    log_record(spdlog::level::err, "journal_failed",
               {{"error", st.error}, {"durable_tick", st.durable_tick}, {"failures", st.failures}, {"room", id_},
                {"code", code_}, {"retry_ms", store::JournalWriter::kRetryEvery.count()}});
    journal_failures_ = st.failures;
  }
  if (journal_failing_ && !st.failing)
    log_record(spdlog::level::info, "journal_recovered",
               {{"durable_tick", st.durable_tick}, {"discarded", st.discarded}, {"room", id_}, {"code", code_}});
  journal_failing_ = st.failing;
  journal_error_ = st.error;
}

}  // namespace fts::server
