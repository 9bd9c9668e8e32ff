#include "app/game_host.hpp"

#include <sodium.h>

#include <algorithm>
#include <array>
#include <filesystem>

#include "app/admission.hpp"

#include "fts/room/snapshot_build.hpp"
#include "fts/protocol/limits.hpp"
#include "fts/room/text.hpp"
#include "fts/sim/config_fields.hpp"

namespace fts::server {
namespace {

std::uint64_t fold_key(const protocol::ServerKey& key) {
  std::uint64_t v = 0x6A09E667F3BCC908ull;
  for (auto b : key) v = (v ^ b) * 0x100000001B3ull;
  return v;
}

}  // namespace

std::uint64_t room_seed(std::uint64_t server_seed, std::uint32_t room_id) {
  if (room_id == 1) return server_seed;
  std::uint64_t z = server_seed + 0x9E3779B97F4A7C15ull * room_id;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

protocol::ServerConfig make_endpoint_config(const Options& o, const sim::MatchConfig& cfg,
                                            const protocol::ServerKey& key) {
  protocol::ServerConfig c;
  c.key = key;
  c.max_players = o.max_players;  // a room's seats
  c.max_sessions_total = (4 * static_cast<std::size_t>(o.max_players) + o.max_spectators) * o.max_rooms;
  c.timeout_ms = o.timeout_ms;
  c.reconnect_window_ms = o.reconnect_window_ms;
  c.idle_timeout_ms = o.idle_timeout_ms;
  apply_address_limits(c, o.max_per_address);
  c.snapshot_max_base_age_ticks = o.tick_rate_hz;  // one second
  if (!o.fleet_secret_path.empty()) {
    // A server of a fleet gives ids from a point in [2^20, 2^31), a one-way hash of its
    // random key (the ids are public, the key is not): two servers' ranges meet with a
    // chance of about (players either served) / 2^31, and a room handed between them keeps
    // its ids (issue 42). Alone, a server's ids start at 1.
    static constexpr char kLabel[] = "fts first player id";
    std::array<std::uint8_t, crypto_generichash_BYTES_MIN> h{};
    crypto_generichash(h.data(), h.size(), reinterpret_cast<const unsigned char*>(kLabel), sizeof kLabel - 1,
                       key.data(), key.size());
    const std::uint32_t r = (std::uint32_t{h[0]} << 24) | (std::uint32_t{h[1]} << 16) | (std::uint32_t{h[2]} << 8) | h[3];
    c.first_player_id = (1u << 20) + r % ((1u << 31) - (1u << 20));
  }
  c.settings.snapshot_rate_hz = o.snapshot_rate_hz;
  c.settings.max_players = o.max_players;
  c.settings.timeout_ms = o.timeout_ms;
  c.settings.reconnect_window_ms = o.reconnect_window_ms;
  // Everything of the match's configuration a client steps or states (config_fields.hpp).
  // (Its tick rate is the rooms' clock's: resolve_match_config() makes them one.)
  c.settings.match = sim::client_part(cfg);
  return c;
}

GameHost::GameHost(const Options& options, const sim::MatchConfig& config, const protocol::ServerKey& key)
    : options_(options),
      config_(config),
      endpoint_([&] {
        auto c = make_endpoint_config(options, config, key);
        c.admit = [this](const protocol::JoinAsk& ask) { return admit(ask); };
        return c;
      }()),
      codes_(fold_key(key)),
      no_match_(sim::make_match(config, options.seed)),
      pool_(options.threads),
      open_scratch_(pool_.threads()) {}

void GameHost::record_to(const std::string& dir, const std::string& version) {
  first_record_ = dir;
  version_ = version;
  if (auto it = rooms_.find(1); it != rooms_.end()) it->second->record_to(dir, version);
}

void GameHost::record_dir(const std::string& dir, const std::string& version) {
  record_dir_ = dir;
  version_ = version;
}

const sim::MatchState& GameHost::match() const { return rooms_.empty() ? no_match_ : rooms_.begin()->second->match(); }

const Room* GameHost::room(std::uint32_t id) const {
  auto it = rooms_.find(id);
  return it == rooms_.end() ? nullptr : it->second.get();
}

const Room* GameHost::room_by_code(const std::string& code) const {
  for (const auto& [id, r] : rooms_)
    if (r->code() == code) return r.get();
  return nullptr;
}

std::vector<std::uint32_t> GameHost::room_ids() const {
  std::vector<std::uint32_t> ids;
  for (const auto& [id, r] : rooms_) ids.push_back(id);
  return ids;
}

Room* GameHost::create_room(bool is_private, const std::string& maker_host) {
  auto code = codes_.next([&](const std::string& c) { return room_by_code(c) != nullptr || journal_exists(c); });
  if (!code) return nullptr;
  const std::uint32_t id = next_room_id_++;
  Room* r = open_room(id, *code, is_private, room_seed(options_.seed, id), config_);
  r->maker_host = maker_host;
  start_journal(*r);
  return r;
}

bool GameHost::reclaim_room(const std::string* maker, std::uint64_t now_ms) {
  const Room* pick = nullptr;
  for (const auto& [id, r] : rooms_) {
    if ((maker && r->maker_host != *maker) || endpoint_.holding_in_room(id) != 0) continue;
    if (!pick || r->last_occupied_ms < pick->last_occupied_ms) pick = r.get();
  }
  if (!pick) return false;
  log_record(spdlog::level::info, "room_reclaimed", {{"room", pick->id()}, {"code", pick->code()}});
  close_room(pick->id(), protocol::ErrorCode::room_closed, "the room was empty and is closed", now_ms);
  return true;
}

std::size_t GameHost::rooms_made_by(const std::string& host) const {
  return static_cast<std::size_t>(
      std::count_if(rooms_.begin(), rooms_.end(), [&](const auto& kv) { return kv.second->maker_host == host; }));
}

Room* GameHost::open_room(std::uint32_t id, const std::string& code, bool is_private, std::uint64_t seed,
                          const sim::MatchConfig& config) {
  auto room = std::make_unique<Room>(id, code, is_private, seed, options_, config);
  // --record names room 1's record, --record-dir every other room's (both may be given).
  const std::string record = id == 1 && !first_record_.empty() ? first_record_
                             : !record_dir_.empty() ? (std::filesystem::path(record_dir_) / ("room-" + std::to_string(id))).string()
                                                    : std::string();
  if (!record.empty() && !room->record_to(record, version_))
    log_record(spdlog::level::err, "record_failed", {{"room", id}, {"path", record}});
  ++rooms_made_;
  room->count_into(&stats_.totals);
  if (profiles_) room->use_profiles(profiles_, unix_s_);
  log_record(spdlog::level::info, "room_open",
             {{"room", id}, {"code", code}, {"private", is_private}, {"seed", room->seed()},
              {"record", room->record_path()}});
  return rooms_.emplace(id, std::move(room)).first->second.get();
}

void GameHost::receive(const std::string& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms) {
  stats_.received(bytes.size());
  now_ms_ = now_ms;
  if (bans_.drops(from, now_ms)) return;  // dropped without an answer: a ban costs the server nothing
  endpoint_.receive_later(from, bytes, now_ms);  // opened at the tick, on the pool
}

std::vector<protocol::Outgoing> GameHost::take_datagrams() {
  std::vector<protocol::Outgoing> out;
  take_datagrams(out);
  return out;
}

void GameHost::take_datagrams(std::vector<protocol::Outgoing>& batch) {
  endpoint_.take_datagrams(batch);
  for (const auto& d : batch) stats_.sent(d.bytes.size());
}

void GameHost::answer_rooms(const protocol::PlayerCommand& pc, std::uint64_t now_ms) {
  endpoint_.send_result(pc.player_id, pc.command.rid, protocol::ResultCode::ok, room_list_text(), now_ms);
}

// "CODE players/seats level phase" per public room, most players first, as many as fit
// in a result's message (PROTOCOL.md 4.6).
std::string GameHost::room_list_text() const {
  std::vector<const Room*> list;
  for (const auto& [id, r] : rooms_)
    if (!r->is_private()) list.push_back(r.get());
  std::stable_sort(list.begin(), list.end(), [&](const Room* a, const Room* b) {
    return endpoint_.seats_in_room(a->id()) > endpoint_.seats_in_room(b->id());
  });
  std::string text;
  for (const Room* r : list) {
    std::string entry = r->code() + " " + std::to_string(endpoint_.seats_in_room(r->id())) + "/" +
                        std::to_string(options_.max_players) + " " + std::to_string(r->match().level) + " " +
                        std::string(sim::to_string(r->match().phase));
    if (text.size() + entry.size() + 2 > protocol::kMaxTextBytes) break;
    text += (text.empty() ? "" : "; ") + entry;
  }
  return text;
}

void GameHost::relay_chat(const protocol::PlayerCommand& pc, std::uint64_t now_ms) {
  const ChatVerdict v = chat_.accept(pc.player_id, pc.command.text, now_ms);
  if (!v.ok) {
    endpoint_.send_result(pc.player_id, pc.command.rid, v.code, std::string(protocol::result_sentence(v.code)), now_ms);
    return;
  }
  endpoint_.send_result(pc.player_id, pc.command.rid, protocol::ResultCode::ok, "", now_ms);
  protocol::Chat line;
  line.from = pc.player_id;
  line.name = "player " + std::to_string(pc.player_id);
  if (const auto s = endpoint_.session_info(pc.player_id)) line.name = s->name;
  // The name the legend shows: a second "ann" speaks as "ann-2".
  if (const Room* r = room(pc.room)) line.name = r->shown_name(pc.player_id, line.name);
  line.text = v.text;
  // Only the sender's room hears it.
  for (const std::uint32_t to : endpoint_.connected_in_room(pc.room)) endpoint_.send_chat(to, line, now_ms);
  log_record(spdlog::level::info, "chat", {{"player", pc.player_id}, {"room", pc.room}, {"chars", v.text.size()}});
}

std::size_t GameHost::announce(const std::string& text, std::uint64_t now_ms) {
  protocol::Chat line;
  line.from = 0;  // the host (PROTOCOL.md: chat)
  line.name = "host";
  line.text = ChatRelay::clean(text, protocol::kMaxTextBytes);
  std::size_t told = 0;
  if (line.text.empty()) return told;
  for (const std::uint32_t to : endpoint_.connected_players()) {
    endpoint_.send_chat(to, line, now_ms);
    ++told;
  }
  return told;
}

void GameHost::dispatch(std::uint64_t now_ms) {
  for (const auto& e : endpoint_.take_events()) {
    using K = protocol::ServerEvent::Kind;
    if (e.kind != K::disconnected) profile_requests_.drop(e.player_id);  // a new session, or none
    if (e.kind == K::connected || e.kind == K::reconnected) {
      members_[e.player_id] = {e.room, e.spectator};
      if (profiles_ && !e.identity.empty() && !e.spectator) profiles_->push(profiles::Seen{e.identity, e.name, unix_s_()});
    }
    if (e.kind == K::released) members_.erase(e.player_id);
    if (auto it = rooms_.find(e.room); it != rooms_.end()) {
      // A player of an adopted room came back: the sender told it where, so it had confirmed.
      // (With its token only: a player taken back by its identity may have come by quick play.)
      if (e.kind == K::reconnected && e.reason == protocol::ServerEvent::kByToken && !e.spectator && it->second->unconfirmed_until_ms != 0)
        confirm_adopted(it->second->code(), "client");
      it->second->on_event(e, endpoint_);
    }
  }
  for (const auto& pi : endpoint_.take_inputs())
    if (auto it = rooms_.find(pi.room); it != rooms_.end()) it->second->on_input(pi, now_ms);
  for (const auto& pc : endpoint_.take_commands()) {
    if (pc.command.op == protocol::CommandOp::rooms) {
      answer_rooms(pc, now_ms);
      continue;
    }
    if (pc.command.op == protocol::CommandOp::chat) {  // spectators may talk too
      relay_chat(pc, now_ms);
      continue;
    }
    if (pc.command.op == protocol::CommandOp::top || pc.command.op == protocol::CommandOp::forget) {
      profile_request(pc, now_ms);  // spectators too: a board is to look at
      continue;
    }
    auto m = members_.find(pc.player_id);
    if (m != members_.end() && m->second.spectator) {
      endpoint_.send_result(pc.player_id, pc.command.rid, protocol::ResultCode::spectator,
                            "a spectator cannot play; join the room to play", now_ms);
      continue;
    }
    auto it = rooms_.find(pc.room);
    if (it == rooms_.end()) continue;
    // A room being handed over steps no more here: a command to it would be lost with it.
    if (it->second->frozen) {
      endpoint_.send_result(pc.player_id, pc.command.rid, protocol::ResultCode::busy,
                            "the room is moving to another server: ask again in a moment", now_ms);
      continue;
    }
    it->second->on_command(pc, endpoint_, now_ms);
  }
}

void GameHost::profile_request(const protocol::PlayerCommand& pc, std::uint64_t now_ms) {
  using protocol::ResultCode;
  const auto refuse = [&](ResultCode code) {
    endpoint_.send_result(pc.player_id, pc.command.rid, code, std::string(protocol::result_sentence(code)), now_ms);
  };
  if (!profiles_) return refuse(ResultCode::no_profiles);
  if (!profile_requests_.may_ask(pc.player_id, now_ms)) return refuse(ResultCode::busy);
  const std::string identity = endpoint_.session_identity(pc.player_id);
  if (pc.command.op == protocol::CommandOp::top) {
    profile_requests_.top(*profiles_, pc.player_id, pc.command.rid, identity);
    return;
  }
  if (identity.empty()) return refuse(ResultCode::guest);
  // No result of the identity's running matches is made from now on: none brings the
  // profile back after the erasure.
  for (auto& [id, r] : rooms_) r->forget_identity(identity);
  if (!profile_requests_.forget(*profiles_, pc.player_id, pc.command.rid, identity))
    return refuse(ResultCode::unavailable);
  log_record(spdlog::level::info, "profile_forget", {{"player", pc.player_id}, {"identity", identity}});
}

void GameHost::answer_profiles(std::uint64_t now_ms) {
  for (auto& a : profile_requests_.take()) {
    if (a.board) endpoint_.send_board(a.player, *a.board, now_ms);
    endpoint_.send_result(a.player, a.rid, a.code, std::move(a.message), now_ms);
  }
}

void GameHost::tick(std::uint64_t now_ms) {
  now_ms_ = now_ms;
  if (const auto stalled = endpoint_.stalled_ms(); stalled != stalled_logged_ms_) {
    log_record(spdlog::level::warn, "stall", {{"ms", stalled - stalled_logged_ms_}, {"total_ms", stalled}});
    stalled_logged_ms_ = stalled;
  }
  // Nobody idles while the players of their room cannot act: lobby, shop, game over; nor
  // does a player out of lives, who watches (the room's job says so: Room::send_snapshots).
  // While a match runs (playing, shop) a player who leaves it is kept for its return until
  // it ends (ServerEndpoint::set_keeps_departed); once nobody plays it any more (everyone
  // left in it has quit), the reconnect window frees them as before, so that the match can
  // end for those who watch.
  for (const auto& [id, r] : rooms_) {
    const sim::MatchState& m = r->match();
    const bool played_on = std::any_of(m.players.begin(), m.players.end(),
                                       [](const sim::Player& p) { return p.in_match() && !p.parked; });
    endpoint_.set_idle_paused(id, m.phase != sim::Phase::playing);
    endpoint_.set_keeps_departed(id, (m.phase == sim::Phase::playing || m.phase == sim::Phase::shop) && played_on);
  }
  // The datagrams received since the last tick: screened, opened and applied to their sessions on
  // the pool, what they left for everyone settled in arrival order.
  {
    const auto jobs = endpoint_.inbox_jobs();  // each a shard of the sessions and their datagrams, no endpoint
    const protocol::ServerEndpoint::ParallelPhase parallel(endpoint_);
    pool_.run(jobs.size(), [&](std::size_t i, std::size_t slot) { jobs[i]->run(open_scratch_[slot]); });
  }
  endpoint_.apply_inbox();
  answer_profiles(now_ms);  // before the timers: the results go out in this tick's packets
  {
    // The sessions' timers, a room's connected sessions per job; the ends settled in order.
    const auto jobs = endpoint_.timer_jobs(now_ms);
    const protocol::ServerEndpoint::ParallelPhase parallel(endpoint_);
    pool_.run(jobs.size(), [&](std::size_t i, std::size_t) { jobs[i].run(); });
  }
  endpoint_.settle_timers(now_ms);
  dispatch(now_ms);
  // The rooms on the pool (the phases: game_host.hpp).
  order_.clear();
  for (auto& [id, r] : rooms_)
    if (!r->frozen) order_.push_back(r.get());
  {
    const protocol::ServerEndpoint::ParallelPhase parallel(endpoint_);
    pool_.run(order_.size(), [&](std::size_t i, std::size_t) { order_[i]->step(now_ms); });
  }
  for (Room* r : order_) r->publish(endpoint_, now_ms);
  if (lanes_.size() < order_.size()) lanes_.resize(order_.size());
  const auto& connected = endpoint_.connected_by_room();  // made again only when sessions changed
  {
    // Each room's job: its room, its connected sessions and its lane; no endpoint.
    const protocol::ServerEndpoint::ParallelPhase parallel(endpoint_);
    pool_.run(order_.size(), [&](std::size_t i, std::size_t) {
      auto it = connected.find(order_[i]->id());
      if (it != connected.end()) order_[i]->send_snapshots(it->second, now_ms, lanes_[i]);
    });
  }
  for (std::size_t i = 0; i < order_.size(); ++i) endpoint_.adopt(lanes_[i]);

  // A room nobody is connected to for room_idle_ms is closed, one that holds nobody after
  // kEmptyRoomMs; while draining, at once (the drain ends when the last room does).
  std::vector<std::uint32_t> idle;
  const std::uint64_t idle_ms = draining_ ? 0 : options_.room_idle_ms;
  for (auto& [id, r] : rooms_) {
    // Being handed over (the peer's answer decides), or adopted and not yet confirmed
    // (forget_unconfirmed decides: its match may go on at the sender, so no results here).
    if (r->frozen || r->unconfirmed_until_ms != 0) continue;
    const bool occupied = connected.count(id) != 0;  // (rooms nobody is connected to are not in it)
    if (!draining_ && (r->last_occupied_ms == 0 || occupied)) {
      r->last_occupied_ms = now_ms;
    } else if (!occupied) {
      const bool empty = endpoint_.holding_in_room(id) == 0;
      if (now_ms - r->last_occupied_ms >= (empty ? std::min(idle_ms, kEmptyRoomMs) : idle_ms)) idle.push_back(id);
    }
  }
  for (auto id : idle) close_room(id, protocol::ErrorCode::room_closed, "the room was empty and is closed", now_ms);
  forget_unconfirmed(now_ms);
  std::erase_if(closing_journals_, [](const auto& j) { return j->stopped(); });
  bans_.expire(now_ms);
}

void GameHost::close_room(std::uint32_t id, protocol::ErrorCode code, const std::string& message,
                          std::uint64_t now_ms) {
  auto it = rooms_.find(id);
  if (it == rooms_.end()) return;
  for (const auto& s : endpoint_.sessions_of_room(id)) endpoint_.kick(s.player_id, code, message, now_ms);
  Room& r = *it->second;
  r.close_careers();  // the players' matches end with the room (before the kicks' releases count as quits)
  log_record(spdlog::level::info, "room_closed",
             {{"room", id}, {"code", r.code()}, {"reason", protocol::to_string(code)}, {"tick", r.match().tick},
              {"state_hash", room::hex16(sim::match_hash(r.match()))}, {"record", r.record_path()}});
  retire_room(it);
}

void GameHost::retire_room(std::map<std::uint32_t, std::unique_ptr<Room>>::iterator it) {
  Room& r = *it->second;
  closed_journal_failures_ += r.journal_failures();
  finish_journal(r);  // first: the seal must not wait for the journal's disk
  r.seal();
  endpoint_.forget_room(r.id());
  rooms_.erase(it);
  if (draining_ && rooms_.empty()) log_record(spdlog::level::info, "drained", {});
}

std::map<std::uint32_t, std::unique_ptr<Room>>::iterator GameHost::room_at(const std::string& code) {
  return std::find_if(rooms_.begin(), rooms_.end(), [&](const auto& kv) { return kv.second->code() == code; });
}

void GameHost::use_profiles(profiles::Writer* writer, std::function<std::int64_t()> unix_s) {
  profiles_ = writer;
  unix_s_ = std::move(unix_s);
  for (auto& [id, r] : rooms_) r->use_profiles(profiles_, unix_s_);
}

void GameHost::kick(std::uint32_t player_id, protocol::ErrorCode code, const std::string& message,
                    std::uint64_t now_ms) {
  endpoint_.kick(player_id, code, message, now_ms);
}

void GameHost::stop_new_rooms() {
  draining_ = true;
  if (rooms_.empty()) log_record(spdlog::level::info, "drained", {});
}

void GameHost::shutdown(std::uint64_t now_ms) {
  // Sealed first: the shutdown's releases are not journaled (a clean stop resumes like
  // a crash).
  for (auto& [id, r] : rooms_) r->seal();
  // Without a journal the rooms end here: their players' matches with them. With one
  // they resume (--resume) and end later, under the same keys.
  if (!journal_base_)
    for (auto& [id, r] : rooms_) r->close_careers();
  endpoint_.shutdown(now_ms);
}

InputTiming GameHost::input_timing() const {
  InputTiming sum;
  for (const auto& [id, r] : rooms_) sum += r->input_timing();
  return sum;
}

}  // namespace fts::server
