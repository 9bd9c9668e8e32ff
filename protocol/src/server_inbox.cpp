// ServerEndpoint's deferred receiving (issue 29): screened at once, queued, opened one
// session per job on the host's threads (an InboxJob: server_jobs.hpp), applied in
// arrival order (server.hpp).
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
  InboxDatagram& q = inbox_[inbox_used_];
  q.player_id = s->player_id;
  q.session_id = s->session_id;
  q.now_ms = now_ms;
  q.bytes.assign(bytes.begin(), bytes.end());
  q.opened.reset();
  auto [j, fresh] = inbox_job_of_.try_emplace(s->player_id, inbox_jobs_used_);
  if (fresh) {
    if (inbox_jobs_used_ == inbox_jobs_.size()) inbox_jobs_.emplace_back();
    inbox_jobs_[inbox_jobs_used_++].datagrams_.clear();
  }
  inbox_jobs_[j->second].datagrams_.push_back(&q);
  ++inbox_used_;
}

void InboxJob::open(std::vector<std::uint8_t>& scratch) {
  if (!seal_) return;  // the session is gone: its datagrams are applied as such
  for (InboxDatagram* d : datagrams_)
    if (d->session_id == session_id_) d->opened.emplace(open_sealed(*seal_, d->bytes, version_, scratch));
}

std::span<InboxJob> ServerEndpoint::inbox_jobs() {
  serial_only("inbox_jobs");
  for (std::size_t i = 0; i < inbox_jobs_used_; ++i) {
    InboxJob& job = inbox_jobs_[i];
    job.seal_ = nullptr;
    job.version_ = config_.version;
    // The player's session now: only its datagrams are opened (an older session's, before
    // a hello replaced it, are applied as gone), and only its seal changes.
    auto it = sessions_.find(job.datagrams_.front()->player_id);
    if (it == sessions_.end()) continue;
    job.seal_ = &it->second.seal;
    job.session_id_ = it->second.session_id;
  }
  return {inbox_jobs_.data(), inbox_jobs_used_};
}

void ServerEndpoint::apply_inbox() {
  serial_only("apply_inbox");
  for (std::size_t at = 0; at < inbox_used_; ++at) {
    InboxDatagram& q = inbox_[at];
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
  inbox_jobs_used_ = 0;
  inbox_job_of_.clear();
}

}  // namespace fts::protocol
