// One client's session on the server (server_session.hpp): its datagrams' headers and seals.
#include "fts/protocol/server_session.hpp"

#include "fts/protocol/constants.hpp"

namespace fts::protocol {

Header ServerSession::next_header(std::uint16_t version, std::uint64_t now_ms) {
  Header h;
  h.version = version;
  h.encoding = encoding;
  h.session = session_id;
  acks.stamp(h, now_ms);
  return h;
}

void ServerSession::seal_into(const Header& h, const std::vector<std::uint8_t>& payload, std::vector<Outgoing>& out,
                              std::vector<Outgoing>& spare) {
  if (spare.empty()) {
    out.emplace_back();
  } else {
    out.push_back(std::move(spare.back()));
    spare.pop_back();
  }
  Outgoing& o = out.back();
  o.to.assign(address);  // within the capacity a sent datagram's address left
  o.bytes.clear();
  seal.seal(h, payload, o.bytes);
  if (o.bytes.size() > kMaxDatagramBytes) {  // never sent; the limits make it unreachable
    spare.push_back(std::move(o));
    out.pop_back();
  }
}

ServerSession* SessionTable::at_address(const Address& address) {
  const auto it = by_address_.find(address);
  return it == by_address_.end() ? nullptr : &by_id_.at(it->second);
}

ServerSession* SessionTable::with_session_id(std::uint32_t id) {
  const auto it = by_session_id_.find(id);
  return it == by_session_id_.end() ? nullptr : &by_id_.at(it->second);
}

void SessionTable::index(const ServerSession& s) {
  by_session_id_[s.session_id] = s.player_id;
  by_address_[s.address] = s.player_id;
}

void SessionTable::unindex(const ServerSession& s) {
  // Only the session's own entries: another session may hold the address by now.
  if (auto it = by_session_id_.find(s.session_id); it != by_session_id_.end() && it->second == s.player_id)
    by_session_id_.erase(it);
  if (auto it = by_address_.find(s.address); it != by_address_.end() && it->second == s.player_id)
    by_address_.erase(it);
}

std::uint32_t SessionTable::next_player_id() {
  // Ids are never reused nor given where a room from another server took them; when they
  // run out (2^32 - 2 sessions in one process life) nobody new is taken.
  while (next_player_id_ != kNoPlayerIdLeft && taken_player_ids_.erase(next_player_id_) != 0)
    reserve_player_ids(next_player_id_);
  return next_player_id_;
}

}  // namespace fts::protocol
