// Rooms that move (issue 42): the host's side of a hand-over, without sockets. The
// channel between the servers is server/net/handover.cpp; what travels is the room's
// journal (store/journal.hpp), which the peer resumes as a restarted server would.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>
#include <sstream>

#include "app/game_host.hpp"
#include "app/room_journals.hpp"
#include "fts/room/match_config_json.hpp"
#include "fts/room/text.hpp"
#include "store/journal.hpp"

namespace fts::server {

namespace fs = std::filesystem;

std::vector<std::variant<GameHost::RoomExport, std::string>> GameHost::export_rooms(
    const std::vector<std::string>& codes) {
  std::vector<std::variant<RoomExport, std::string>> out(codes.size());
  std::vector<Room*> rooms(codes.size(), nullptr);
  // Every room's writer is asked to sync first, then each is waited for: the rooms'
  // writers sync at once (one after another, 64 rooms' fsyncs took the loop a while).
  for (std::size_t i = 0; i < codes.size(); ++i) {
    const auto norm = normalize_room_code(codes[i]);
    const auto it = norm ? room_at(*norm) : rooms_.end();
    Room* r = it == rooms_.end() ? nullptr : it->second.get();
    if (!r) out[i] = "no room " + codes[i] + " on this server";
    else if (r->frozen) out[i] = "room " + r->code() + " is being handed over already";
    else if (r->unconfirmed_until_ms != 0)
      out[i] = "room " + r->code() + " is still arriving here (its server has not confirmed it)";
    else if (!journal_base_ || !r->journal()) out[i] = "room " + r->code() + " keeps no journal (--journal-dir)";
    else if (std::find(rooms.begin(), rooms.end(), r) != rooms.end()) out[i] = "room " + r->code() + " named twice";
    else rooms[i] = r, r->start_sync();
  }
  for (std::size_t i = 0; i < codes.size(); ++i) {
    Room* r = rooms[i];
    if (!r) continue;
    if (!r->finish_sync()) {
      out[i] = "room " + r->code() + "'s journal is failing or dropped records: it stays here";
      continue;
    }
    RoomExport ex;
    ex.code = r->code();
    ex.tick = r->match().tick;
    // The newest segment alone: it begins with the checkpoint start_sync wrote (older
    // ones are not needed, and the writer may be removing them now).
    const auto segments = store::list_segments(journal_base_->dir / r->code());
    if (segments.empty()) {
      out[i] = "room " + r->code() + " has no journal segment yet";
      continue;
    }
    const auto& path = segments.back().second;
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) {
      out[i] = "cannot read " + path.string();
      continue;
    }
    ex.files.emplace_back(path.filename().string(), std::move(text));
    r->frozen = true;
    log_record(spdlog::level::info, "handover_start", {{"room", r->id()}, {"code", r->code()}, {"tick", ex.tick},
                                                        {"segments", ex.files.size()}});
    out[i] = std::move(ex);
  }
  return out;
}

std::size_t GameHost::room_moved(const std::string& code, const std::string& address, std::uint64_t now_ms) {
  const auto it = room_at(code);
  if (it == rooms_.end()) return 0;
  Room& r = *it->second;
  const std::uint32_t id = r.id();
  if (journal_base_) {  // first: from here a restart must not bring the room back (JournalRoot)
    std::ofstream mark(journal_base_->dir / code / JournalRoot::kMovedMark, std::ios::trunc);
  }
  // The match goes on at the peer, and its results are made there: none here (no
  // close_careers), and the journal's directory goes (the peer keeps its own).
  const std::size_t told = endpoint_.move_room(id, address, code, now_ms);
  log_record(spdlog::level::info, "room_moved",
             {{"room", id}, {"code", code}, {"to", address}, {"tick", r.match().tick}, {"clients_told", told},
              {"state_hash", room::hex16(sim::match_hash(r.match()))}});
  ++rooms_moved_;
  retire_room(it);
  return told;
}

void GameHost::room_kept(const std::string& code, const std::string& why) {
  const auto it = room_at(code);
  if (it == rooms_.end()) return;
  it->second->frozen = false;
  ++handovers_refused_;
  log_record(spdlog::level::warn, "handover_refused", {{"room", it->first}, {"code", code}, {"reason", why}});
}

std::string GameHost::adopt_room(const std::string& code, const std::vector<std::pair<std::string, std::string>>& files,
                                 std::uint64_t now_ms) {
  const auto began = std::chrono::steady_clock::now();
  const auto refuse = [&](const std::string& why) {
    log_record(spdlog::level::warn, "adopt_refused", {{"code", code}, {"reason", why}});
    return why;
  };
  const auto norm = normalize_room_code(code);
  if (!norm || *norm != code) return refuse("not a room code");
  if (!journal_base_) return refuse("this server keeps no journals (--journal-dir)");
  if (draining_) return refuse("this server is draining");
  if (room_by_code(code)) return refuse("room " + code + " is open here already (handed over twice?)");
  if (journal_exists(code)) return refuse("a journal of room " + code + " is here already");
  if (rooms_.size() >= options_.max_rooms) return refuse("full: this server has --max-rooms rooms");
  if (files.empty()) return refuse("no journal segment came");
  for (const auto& [name, text] : files) {
    const bool segment = name.size() == store::segment_name(1).size() && name.starts_with("journal-") &&
                         name.ends_with(".jsonl") && name.find('/') == std::string::npos;
    if (!segment) return refuse("a file that is not a journal segment came");
  }
  const fs::path incoming = journal_base_->dir / (code + ".incoming");
  const fs::path dir = journal_base_->dir / code;
  std::error_code ec;
  fs::remove_all(incoming, ec);
  fs::create_directories(incoming, ec);
  // The segments, and the mark of a room held until the sender confirms it (resume_room
  // holds a room whose directory has it: a restart in between holds it again).
  std::ofstream(incoming / JournalRoot::kUnconfirmedMark, std::ios::trunc);
  for (const auto& [name, text] : files) {
    std::ofstream out(incoming / name, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) {
      fs::remove_all(incoming, ec);
      return refuse("cannot write the journal here: " + (incoming / name).string());
    }
  }
  const auto read = store::read_journal(incoming);
  const auto* room = std::get_if<store::ResumedRoom>(&read);
  std::string why;
  if (!room) why = "its journal does not read: " + std::get<std::string>(read);
  else if (room->room != code) why = "its journal names room " + room->room;
  else if (room::match_config_to_json(room->config).dump() != room::match_config_to_json(config_).dump())
    why = "its match configuration differs from this server's";
  else if (!room->damage.empty()) why = "its journal is damaged: " + room->damage;
  if (why.empty()) {
    // Its players keep their ids (their clients' tokens name them): none may be in use here.
    for (const auto& s : room->sessions)
      if (endpoint_.has_session(s.player)) why = "player id " + std::to_string(s.player) + " is in use here";
  }
  if (why.empty()) {
    fs::rename(incoming, dir, ec);
    if (ec) why = "cannot keep its journal here: " + ec.message();
  }
  if (!why.empty()) {
    fs::remove_all(incoming, ec);
    return refuse(why);
  }
  if (!resume_room(*room, now_ms, true)) {
    fs::remove_all(dir, ec);
    return refuse("the server did not take it (see resume_refused)");
  }
  ++rooms_adopted_;
  log_record(spdlog::level::info, "room_adopted",
             {{"code", code}, {"tick", room->state.tick}, {"level", room->state.level},
              {"sessions", room->sessions.size()}, {"ticks_replayed", room->ticks_replayed},
              {"hash", room::hex16(sim::match_hash(room->state))}, {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count()}});
  return "";
}

bool GameHost::confirm_adopted(const std::string& code, const char* by) {
  const auto it = room_at(code);
  if (it == rooms_.end() || it->second->unconfirmed_until_ms == 0) return false;
  it->second->unconfirmed_until_ms = 0;
  std::error_code ec;
  if (journal_base_) fs::remove(journal_base_->dir / code / JournalRoot::kUnconfirmedMark, ec);
  log_record(spdlog::level::info, "adopt_confirmed", {{"code", code}, {"by", by}});
  return true;
}

bool GameHost::unconfirmed(const std::string& code) const {
  const Room* r = room_by_code(code);
  return r && r->unconfirmed_until_ms != 0;
}

void GameHost::forget_unconfirmed(std::uint64_t now_ms) {
  for (auto it = rooms_.begin(); it != rooms_.end();) {
    const auto next = std::next(it);
    Room& r = *it->second;
    if (r.unconfirmed_until_ms != 0 && !r.frozen && now_ms >= r.unconfirmed_until_ms) {
      log_record(spdlog::level::warn, "adopt_forgotten",
                 {{"room", r.id()}, {"code", r.code()}, {"tick", r.match().tick},
                  {"reason", "neither the sender's confirmation nor a client of the room came: the sender kept it"}});
      ++rooms_forgotten_;
      // No results (the match goes on at the sender); the journal's directory goes with
      // the room, mark and all, so no restart brings this copy back.
      for (const auto& s : endpoint_.sessions_of_room(r.id()))
        endpoint_.kick(s.player_id, protocol::ErrorCode::room_closed, "the room stayed on its server", now_ms);
      retire_room(it);
    }
    it = next;
  }
}

}  // namespace fts::server
