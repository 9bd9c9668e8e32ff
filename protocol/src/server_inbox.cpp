// ServerEndpoint's deferred receiving (issue 29): screened at once, queued, opened one
// session per job on the host's threads, applied in arrival order (server.hpp).
#include "fts/protocol/server.hpp"

namespace fts::protocol {

ServerEndpoint::Session* ServerEndpoint::live_session(std::uint32_t player_id, std::uint32_t session_id) {
  auto it = sessions_.find(player_id);
  if (it == sessions_.end() || it->second.session_id != session_id || !it->second.connected) return nullptr;
  return &it->second;
}

void ServerEndpoint::receive_later(const Address& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms) {
  serial_only("receive_later");
  Session* s = screen(from, bytes, now_ms);
  if (!s) return;
  if (inbox_used_ >= kMaxInbox) return rejects_.add(Reject::rate_limited);
  if (inbox_used_ == inbox_.size()) inbox_.emplace_back();
  Queued& q = inbox_[inbox_used_];
  q.player_id = s->player_id;
  q.session_id = s->session_id;
  q.now_ms = now_ms;
  q.bytes.assign(bytes.begin(), bytes.end());
  q.opened.reset();
  auto [g, fresh] = inbox_group_of_.try_emplace(s->player_id, inbox_groups_used_);
  if (fresh) {
    if (inbox_groups_used_ == inbox_groups_.size()) inbox_groups_.emplace_back();
    inbox_groups_[inbox_groups_used_++].clear();
  }
  inbox_groups_[g->second].push_back(inbox_used_++);
}

void ServerEndpoint::open_inbox(std::size_t i, std::vector<std::uint8_t>& plain) {
  for (const std::size_t at : inbox_groups_[i]) {
    Queued& q = inbox_[at];
    // Only the session's own seal changes: another session's open may run beside this one.
    auto it = sessions_.find(q.player_id);
    if (it == sessions_.end() || it->second.session_id != q.session_id) continue;  // gone: applied as such
    q.opened.emplace(open_sealed(it->second.seal, q.bytes, config_.version, plain));
  }
}

void ServerEndpoint::apply_inbox() {
  serial_only("apply_inbox");
  for (std::size_t at = 0; at < inbox_used_; ++at) {
    Queued& q = inbox_[at];
    // An earlier datagram may have ended the session (bye, overflow) or a hello replaced it.
    Session* s = live_session(q.player_id, q.session_id);
    if (!s || !q.opened) {
      rejects_.add(Reject::unknown_session);
      continue;
    }
    handle_opened(*s, *q.opened, q.now_ms);
    q.opened.reset();
  }
  inbox_used_ = 0;
  inbox_groups_used_ = 0;
  inbox_group_of_.clear();
}

}  // namespace fts::protocol
