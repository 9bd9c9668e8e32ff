// ServerEndpoint's deferred receiving (issues 29, 39): screened at once, queued, opened and
// applied one session per job on the host's threads (an InboxJob: server_jobs.hpp), then
// what they left for everyone settled in arrival order (settle).
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
  q.applied.clear();
  if (s->inbox_round != inbox_round_) {  // the session's first datagram of the tick: a job of its own
    s->inbox_round = inbox_round_;
    s->inbox_job = inbox_jobs_used_;
    if (inbox_jobs_used_ == inbox_jobs_.size()) inbox_jobs_.emplace_back();
    inbox_jobs_[inbox_jobs_used_++].datagrams_.clear();
  }
  inbox_jobs_[s->inbox_job].datagrams_.push_back(&q);
  ++inbox_used_;
}

void InboxJob::run(std::vector<std::uint8_t>& scratch) {
  bool ended = false;
  for (InboxDatagram* d : datagrams_) {  // (each Applied cleared when queued: receive_later)
    if (!session_ || ended || d->session_id != session_->session_id) {
      rejects_.add(Reject::unknown_session);
      continue;
    }
    session_->apply(open_sealed(session_->seal, d->bytes, config_->version, scratch), d->now_ms, *config_, d->applied,
                    rejects_);
    ended = d->applied.end != Applied::End::none;
  }
}

std::span<InboxJob> ServerEndpoint::inbox_jobs() {
  serial_only("inbox_jobs");
  for (std::size_t i = 0; i < inbox_jobs_used_; ++i) {
    InboxJob& job = inbox_jobs_[i];
    job.config_ = &config_;  // (its rejects_ are zero: apply_inbox took them last time)
    // The session its last datagram came for, if still connected under that id (a hashed
    // lookup): datagrams of an older one, before a hello replaced it, are counted as gone;
    // so are all, when a hello replaced it after the last.
    ServerSession* s = sessions_.with_session_id(job.datagrams_.back()->session_id);
    job.session_ = s && s->player_id == job.datagrams_.back()->player_id ? s : nullptr;
  }
  return {inbox_jobs_.data(), inbox_jobs_used_};
}

void ServerEndpoint::apply_inbox() {
  serial_only("apply_inbox");
  for (std::size_t i = 0; i < inbox_jobs_used_; ++i) {
    rejects_.add(inbox_jobs_[i].rejects_);
    inbox_jobs_[i].rejects_ = {};  // counted once, whatever calls come next
  }
  for (std::size_t at = 0; at < inbox_used_; ++at) {
    InboxDatagram& q = inbox_[at];
    settle(q.player_id, q.session_id, q.applied, q.now_ms);
  }
  inbox_used_ = 0;
  inbox_jobs_used_ = 0;
  ++inbox_round_;
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
