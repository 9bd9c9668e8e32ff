// How a server session ends or comes back: closed over a queue cap, its connection lost,
// released, kicked by the host, all told at shutdown; restored from a journal.
#include "fts/protocol/server.hpp"

namespace fts::protocol {

// A session over a queue cap: what it queued is forgotten and it is closed, as yojimbo
// disconnects a client whose queue is full. Invalidates `s`.
void ServerEndpoint::overflow(Session& s, const std::string& what, std::uint64_t now_ms) {
  rejects_.add(Reject::overflow);
  const std::uint32_t id = s.player_id;
  std::erase_if(commands_, [&](const PlayerCommand& c) { return c.player_id == id; });
  std::erase_if(inputs_, [&](const PlayerInput& i) { return i.player_id == id; });
  kick(id, ErrorCode::overflow,
       "too many " + what + " waiting on this connection (results are not acknowledged); it is closed",
       now_ms);
}

void ServerEndpoint::drop_connection(Session& s, const std::string& reason, std::uint64_t now_ms) {
  s.connected = false;
  s.disconnected_ms = now_ms;
  sessions_.unindex(s);
  events_.push_back({ServerEvent::Kind::disconnected, s.player_id, s.name, reason, s.quit, s.room, s.spectator, s.identity});
}

void ServerEndpoint::release(std::uint32_t player_id, const std::string& reason) {
  auto it = sessions_.find(player_id);
  if (it == sessions_.end()) return;
  events_.push_back({ServerEvent::Kind::released, player_id, it->second.name, reason, false, it->second.room,
                     it->second.spectator, it->second.identity});
  sessions_.erase(it);  // and its index entries
}

void ServerEndpoint::kick(std::uint32_t player_id, ErrorCode code, const std::string& message, std::uint64_t now_ms) {
  serial_only("kick");
  auto it = sessions_.find(player_id);
  if (it == sessions_.end()) return;
  if (it->second.connected) send_packet(it->second, {make_error(code, message.substr(0, kMaxTextBytes))}, false, now_ms);
  release(player_id, std::string(to_string(code)));
}

bool ServerEndpoint::restore_session(const RestoredSession& r, std::uint64_t now_ms, std::uint32_t room,
                                     const std::string& room_code) {
  serial_only("restore_session");
  // A gap since the last call is a stall of the sessions there were (observe_time moves
  // their clocks on by it): it must not move this one's, which begins now. Without this,
  // a room adopted after a long tick (64 rooms handed over at once) had its sessions'
  // disconnection in the future: kept at once, released "match over" at once.
  observe_time(now_ms);
  const bool hex32 = r.token_verifier.size() == 32 &&
                     std::all_of(r.token_verifier.begin(), r.token_verifier.end(),
                                 [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
  if (r.player_id == 0 || sessions_.count(r.player_id) || !hex32 || !name_problem(r.name).empty() ||
      sessions_.size() >= config_.max_sessions())
    return false;
  if (r.foreign) take_player_id(r.player_id);
  else reserve_player_ids(r.player_id);
  Session& s = sessions_[r.player_id];  // (the generation moves: members_of reads the room set below)
  s.player_id = r.player_id;
  s.name = r.name;
  s.verifier = r.token_verifier;
  s.identity = r.identity.size() == kFingerprintHex ? r.identity : std::string();
  s.quit = r.quit;
  s.room = room;
  s.room_code = room_code;
  s.played = true;  // it held a seat: the reconnect window applies
  s.connected = false;
  s.disconnected_ms = now_ms;
  s.last_active_ms = now_ms;
  events_.push_back({ServerEvent::Kind::disconnected, s.player_id, s.name, "restart", s.quit, s.room, false, s.identity});
  return true;
}

std::string ServerEndpoint::session_identity(std::uint32_t player_id) const {
  auto it = sessions_.find(player_id);
  return it == sessions_.end() ? std::string() : it->second.identity;
}

std::string ServerEndpoint::session_verifier(std::uint32_t player_id) const {
  auto it = sessions_.find(player_id);
  return it == sessions_.end() ? std::string() : it->second.verifier;
}

std::size_t ServerEndpoint::move_room(std::uint32_t room, const std::string& address, const std::string& room_code,
                                      std::uint64_t now_ms) {
  serial_only("move_room");
  std::vector<std::uint32_t> ids;
  for (const auto& [id, s] : sessions_)
    if (s.room == room) ids.push_back(id);
  std::size_t told = 0;
  for (auto id : ids) {
    Session& s = sessions_.at(id);
    if (s.connected) {
      for (int i = 0; i < 3; ++i) send_packet(s, {Moved{address, room_code}}, false, now_ms);
      ++told;
    }
    release(id, "moved");
  }
  return told;
}

void ServerEndpoint::shutdown(std::uint64_t now_ms) {
  serial_only("shutdown");
  std::vector<std::uint32_t> ids;
  for (const auto& [id, s] : sessions_) ids.push_back(id);
  for (auto id : ids) kick(id, ErrorCode::shutdown, "the server is shutting down", now_ms);
}

}  // namespace fts::protocol
