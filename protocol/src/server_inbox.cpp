// ServerEndpoint's deferred receiving (issues 29, 39): the sender screened at once (its
// host's rate, the header), queued by its session id's shard; its session screened, the
// datagram opened and applied one shard per job on the host's threads (an InboxJob:
// server_jobs.hpp), then what they left for everyone settled in arrival order (settle).
#include <algorithm>

#include "fts/protocol/server.hpp"

namespace fts::protocol {

ServerEndpoint::Session* ServerEndpoint::live_session(std::uint32_t player_id, std::uint32_t session_id) {
  auto it = sessions_.find(player_id);
  if (it == sessions_.end() || it->second.session_id != session_id || !it->second.connected) return nullptr;
  return &it->second;
}

void ServerEndpoint::receive_later(const Address& from, std::span<const std::uint8_t> bytes, std::uint64_t now_ms) {
  serial_only("receive_later");
  const std::uint32_t session_id = screen_sender(from, bytes, now_ms);
  if (session_id == 0) return;
  if (inbox_used_ >= kMaxInbox) return rejects_.add(Reject::rate_limited);
  if (inbox_used_ == inbox_.size()) inbox_.emplace_back();
  InboxDatagram& q = inbox_[inbox_used_++];
  q.session_id = session_id;
  q.player_id = 0;
  q.now_ms = now_ms;
  q.from = from;
  q.bytes.assign(bytes.begin(), bytes.end());
  q.applied.clear();
  InboxJob& job = inbox_jobs_[SessionShard::of(session_id)];
  if (job.datagrams_.empty()) inbox_queued_.push_back(&job);
  job.datagrams_.push_back(&q);
}

void InboxJob::run(std::vector<std::uint8_t>& scratch) {
  ended_.clear();
  for (InboxDatagram* d : datagrams_) {  // (each Applied cleared when queued: receive_later)
    ServerSession* s = session_for(sessions_.find(d->session_id), d->from, rejects_);
    if (s == nullptr) continue;
    if (std::find(ended_.begin(), ended_.end(), d->session_id) != ended_.end()) {
      rejects_.add(Reject::unknown_session);
      continue;
    }
    d->player_id = s->player_id;
    s->apply(open_sealed(s->seal, d->bytes, config_->version, scratch), d->now_ms, *config_, d->applied, rejects_);
    if (d->applied.end != Applied::End::none) ended_.push_back(d->session_id);
  }
}

std::span<InboxJob* const> ServerEndpoint::inbox_jobs() {
  serial_only("inbox_jobs");
  for (InboxJob* job : inbox_queued_) {  // (its rejects_ are zero: apply_inbox took them)
    job->sessions_ = sessions_.shard(static_cast<unsigned>(job - inbox_jobs_.data()));
    job->config_ = &config_;
  }
  return inbox_queued_;
}

void ServerEndpoint::apply_inbox() {
  serial_only("apply_inbox");
  for (InboxJob* job : inbox_queued_) {
    rejects_.add(job->rejects_);
    job->rejects_ = {};  // counted once, whatever calls come next
    job->datagrams_.clear();
  }
  inbox_queued_.clear();
  for (std::size_t at = 0; at < inbox_used_; ++at) {
    InboxDatagram& q = inbox_[at];
    if (q.player_id != 0) settle(q.player_id, q.session_id, q.applied, q.now_ms);
  }
  inbox_used_ = 0;
}

void ServerEndpoint::settle(std::uint32_t player_id, std::uint32_t session_id, Applied& applied,
                            std::uint64_t now_ms) {
  inputs_.insert(inputs_.end(), applied.inputs.begin(), applied.inputs.end());
  for (auto& c : applied.commands) commands_.push_back(std::move(c));
  if (applied.end == Applied::End::none) return;
  Session* s = live_session(player_id, session_id);
  if (!s) return;
  if (applied.end == Applied::End::overflow) return overflow(*s, applied.why, now_ms);
  // A player who quits gives its seat up at once; its progress stays for the window.
  s->quit = true;
  drop_connection(*s, applied.why.empty() ? "bye" : applied.why, now_ms);
  // A health check leaves no player behind: its slot is free at once.
  if (applied.why == kProbeByeReason) release(player_id, kProbeByeReason);
}

}  // namespace fts::protocol
