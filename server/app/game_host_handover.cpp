// Rooms that move (issue 42): the host's side of a hand-over, without sockets. The
// channel between the servers is server/net/handover.cpp; what travels is the room's
// journal (store/journal.hpp), which the peer resumes as a restarted server would.
#include <fstream>
#include <iterator>
#include <sstream>

#include "app/game_host.hpp"
#include "fts/room/match_config_json.hpp"
#include "fts/room/text.hpp"
#include "store/journal.hpp"

namespace fts::server {

namespace fs = std::filesystem;

std::variant<GameHost::RoomExport, std::string> GameHost::export_room(const std::string& code) {
  const auto norm = normalize_room_code(code);
  const auto it = norm ? room_at(*norm) : rooms_.end();
  if (it == rooms_.end()) return "no room " + code + " on this server";
  Room* r = it->second.get();
  if (r->frozen) return "room " + r->code() + " is being handed over already";
  if (!journal_base_ || !r->journal()) return "room " + r->code() + " keeps no journal (--journal-dir)";
  if (!r->sync_journal()) return "room " + r->code() + "'s journal is failing or dropped records: it stays here";
  RoomExport out;
  out.code = r->code();
  out.tick = r->match().tick;
  // The newest segment alone: it begins with the checkpoint sync_journal wrote (older
  // ones are not needed, and the writer may be removing them now).
  const auto segments = store::list_segments(journal_base_->dir / r->code());
  if (!segments.empty()) {
    const auto& path = segments.back().second;
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) return "cannot read " + path.string();
    out.files.emplace_back(path.filename().string(), std::move(text));
  }
  if (out.files.empty()) return "room " + r->code() + " has no journal segment yet";
  r->frozen = true;
  log_record(spdlog::level::info, "handover_start", {{"room", r->id()}, {"code", r->code()}, {"tick", out.tick},
                                                      {"segments", out.files.size()}});
  return out;
}

std::size_t GameHost::room_moved(const std::string& code, const std::string& address, std::uint64_t now_ms) {
  const auto it = room_at(code);
  if (it == rooms_.end()) return 0;
  Room& r = *it->second;
  const std::uint32_t id = r.id();
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
              {"hash", room::hex16(sim::match_hash(room->state))}});
  return "";
}

}  // namespace fts::server
