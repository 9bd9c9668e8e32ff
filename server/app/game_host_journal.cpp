// GameHost's part of the crash-safe journal (issue 15): one journal per room, in the
// directory named after the room's code; rooms rebuilt from their journals.
#include <filesystem>

#include "app/game_host.hpp"
#include "app/room_codes.hpp"
#include "app/room_journals.hpp"
#include "fts/room/snapshot_build.hpp"

namespace fts::server {

std::uint32_t GameHost::wire_event_count(std::int64_t tick, const sim::TickOutput& out) {
  std::vector<protocol::Event> wire;
  room::append_wire_events(tick + 1, out.events, wire);
  return static_cast<std::uint32_t>(wire.size());
}

void GameHost::journal_rooms(store::JournalConfig base) {
  journal_base_ = std::move(base);
  for (auto& [id, r] : rooms_)
    if (!r->journal()) start_journal(*r);
}

bool GameHost::journal_exists(const std::string& code) const {
  std::error_code ec;
  return journal_base_ && std::filesystem::exists(journal_base_->dir / code, ec);
}

void GameHost::start_journal(Room& r) {
  if (!journal_base_) return;
  store::JournalConfig c = *journal_base_;
  c.dir = journal_base_->dir / r.code();
  c.room = r.code();
  c.room_id = r.id();
  c.is_private = r.is_private();
  c.seed = r.seed();
  r.journal_to(std::move(c), endpoint_);
}

GameHost::JournalHealth GameHost::journal_health() const {
  JournalHealth h;
  h.failures = closed_journal_failures_;
  for (const auto& [id, r] : rooms_) {
    if (!r->journal()) continue;
    ++h.rooms;
    h.failures += r->journal_failures();
    if (!r->journal_failing()) continue;
    ++h.failing;
    if (h.error.empty()) h.error = r->code() + ": " + r->journal_error();
  }
  return h;
}

void GameHost::finish_journal(Room& r) {
  if (auto j = r.finish_journal()) closing_journals_.push_back(std::move(j));
  if (auto j = r.finish_record()) closing_journals_.push_back(std::move(j));
}

bool GameHost::resume_room(const store::ResumedRoom& resumed, std::uint64_t now_ms, bool foreign) {
  auto refused = [&](const std::string& why) {
    log_record(spdlog::level::err, "resume_refused", {{"code", resumed.room}, {"reason", why}});
    return false;
  };
  const auto code = normalize_room_code(resumed.room);
  if (!code || *code != resumed.room) return refused("not a room code");
  if (room_by_code(*code)) return refused("a room with this code is open already");
  if (rooms_.size() >= options_.max_rooms) return refused("the server has --max-rooms rooms already");
  const std::uint32_t id = resumed.room_id != 0 && !rooms_.count(resumed.room_id) ? resumed.room_id : next_room_id_;
  next_room_id_ = std::max(next_room_id_, id + 1);
  Room* r = open_room(id, *code, resumed.is_private, resumed.seed, resumed.config);
  r->resume_from(resumed);
  endpoint_.set_server_tick(id, static_cast<std::uint32_t>(resumed.state.tick));
  // No newcomer gets an id the resumed match names (a player, a ball's owner or credit):
  // ids are never reused (ServerEndpoint::reserve_player_ids, take_player_id).
  const auto keep_out = [&](std::uint32_t player) {
    if (foreign) endpoint_.take_player_id(player);
    else endpoint_.reserve_player_ids(player);
  };
  for (const auto& p : resumed.state.players) keep_out(p.id.value);
  for (const auto& [ball, b] : resumed.state.bodies) {
    keep_out(b.owner.value);
    keep_out(b.credit.value);
  }
  for (const auto& s : resumed.sessions) {
    // Each comes back as "disconnected" in the next tick's events: the match marks it away.
    if (endpoint_.restore_session({s.player, s.name, s.verifier, s.quit, s.identity, foreign}, now_ms, id, *code)) {
      members_[s.player] = {id, false};
      r->restore_career(s);  // the player's match so far: its result key and counts
    }
    else
      log_record(spdlog::level::warn, "resume_session_refused", {{"player", s.player}, {"name", s.name}, {"room", id}});
  }
  start_journal(*r);  // a new segment after the old ones, with the sessions restored
  // Adopted from a peer and not confirmed yet (adopt_room): held until it is, or forgotten.
  std::error_code ec;
  if (journal_base_ && std::filesystem::exists(journal_base_->dir / *code / JournalRoot::kUnconfirmedMark, ec)) {
    r->unconfirmed_until_ms = now_ms + kUnconfirmedMs;
    log_record(spdlog::level::info, "adopt_unconfirmed", {{"code", *code}, {"forgotten_in_ms", kUnconfirmedMs}});
  }
  return true;
}

const store::JournalWriter* GameHost::journal(std::uint32_t room_id) const {
  auto it = rooms_.find(room_id);
  return it == rooms_.end() ? nullptr : it->second->journal();
}

store::JournalWriter* GameHost::journal(std::uint32_t room_id) {
  auto it = rooms_.find(room_id);
  return it == rooms_.end() ? nullptr : it->second->journal();
}

}  // namespace fts::server
