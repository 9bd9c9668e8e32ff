// ServerEndpoint's timers (issue 39): what time alone does to the sessions. The connected
// ones are kept alive per room in a TimerJob (server_jobs.hpp: on the host's pool, or here
// one after the other); what those jobs find, and the sessions not connected, are settled
// serially, in room order and then player id order, whatever the thread count.
#include "fts/protocol/server.hpp"

#include <algorithm>

namespace fts::protocol {

void TimerJob::run() {  // (its lists emptied by timer_jobs, which handed it out)
  const ServerConfig& c = *config_;
  for (ServerSession* s : members_->sessions_) {
    if (s->spectator || s->watching || idle_paused_) s->last_active_ms = now_ms_;
    if (now_ms_ - s->last_receive_ms >= c.timeout_ms) {
      timed_out_.push_back(s);
      continue;
    }
    if (c.idle_timeout_ms != 0 && now_ms_ - s->last_active_ms >= c.idle_timeout_ms) {
      idle_.push_back(s);
      continue;
    }
    if (s->results.due(now_ms_, c.resend_ms) || s->chats.due(now_ms_, c.resend_ms) ||
        now_ms_ - s->last_send_ms >= c.heartbeat_ms)
      seal_packet(*s, c.version, {}, true, c.resend_ms, now_ms_, lane_);
  }
}

void ServerEndpoint::update(std::uint64_t now_ms) {
  serial_only("update");
  for (TimerJob& job : timer_jobs(now_ms)) job.run();
  settle_timers(now_ms);
}

std::span<TimerJob> ServerEndpoint::timer_jobs(std::uint64_t now_ms) {
  serial_only("timer_jobs");
  observe_time(now_ms);  // a stall of the server's own moves the clocks first
  if (now_ms >= last_forget_ms_ + 1000) {
    limits_.forget_quiet(now_ms);
    last_forget_ms_ = now_ms;
  }
  refresh_rooms();
  if (timer_jobs_.size() < by_room_.size()) timer_jobs_.resize(by_room_.size());
  timer_jobs_used_ = 0;
  for (const auto& [room, members] : by_room_) {
    TimerJob& job = timer_jobs_[timer_jobs_used_++];
    job.members_ = &members;
    job.config_ = &config_;
    job.now_ms_ = now_ms;
    job.idle_paused_ = terms(room).idle_paused;
    // Empty, unless a run was not settled (a job threw): what it found is stale then.
    job.timed_out_.clear();
    job.idle_.clear();
    job.lane_.out.clear();
  }
  return {timer_jobs_.data(), timer_jobs_used_};
}

void ServerEndpoint::settle_timers(std::uint64_t now_ms) {
  serial_only("settle_timers");
  // Ids, not sessions: releasing one erases it.
  std::vector<std::uint32_t> never_played, idle;
  for (std::size_t i = 0; i < timer_jobs_used_; ++i) {
    TimerJob& job = timer_jobs_[i];
    adopt(job.lane_);
    for (ServerSession* s : job.timed_out_) {
      drop_connection(*s, "timeout", now_ms);
      // A session that never played (a probe whose bye was lost, a script that only shook
      // hands) holds no slot: it is freed at its time-out.
      if (!s->played) never_played.push_back(s->player_id);
    }
    for (ServerSession* s : job.idle_) idle.push_back(s->player_id);
  }
  timer_jobs_used_ = 0;

  // The sessions not connected (those that timed out just now among them): their
  // reconnect windows.
  refresh_rooms();
  std::vector<std::uint32_t> expired, keep;
  std::map<std::uint32_t, std::size_t> kept_in_room;
  for (const Session* s : held_)
    if (s->kept) ++kept_in_room[s->room];
  for (const Session* s : held_) {
    if (!s->played && std::find(never_played.begin(), never_played.end(), s->player_id) != never_played.end())
      continue;
    if (now_ms - s->disconnected_ms < config_.reconnect_window_ms || (s->kept && terms(s->room).keeps_departed))
      continue;
    if (!s->kept && s->played && !s->spectator && terms(s->room).keeps_departed) keep.push_back(s->player_id);
    else expired.push_back(s->player_id);
  }
  // A departed player of a running match stays that player (set_keeps_departed): past
  // the window it gives its seat up as after a quit, its progress kept for the match.
  for (auto id : keep) {
    Session& s = sessions_.at(id);
    if (kept_in_room[s.room] >= kMaxKeptPerRoom) {
      expired.push_back(id);
      continue;
    }
    ++kept_in_room[s.room];
    s.kept = true;
    // Its seat is free; the match parks its ball (a quit, again for one that quit already:
    // parking is idempotent), and the host logs it as kept.
    s.quit = true;
    events_.push_back({ServerEvent::Kind::disconnected, s.player_id, s.name, "kept", true, s.room, s.spectator, s.identity});
  }
  for (auto id : expired) release(id, sessions_.at(id).kept ? "match over" : "reconnect window over");
  for (auto id : never_played) release(id, "timeout");
  // An idle player gives its seat up as if it had quit: what it earned is kept for the
  // reconnect window, and while its room's match runs until it ends (its token takes it
  // back while a seat is free).
  for (auto id : idle) {
    rejects_.add(Reject::idle);
    Session& s = sessions_.at(id);
    send_packet(s,
                {make_error(ErrorCode::idle, "no input for " + std::to_string(config_.idle_timeout_ms / 1000) +
                                             " s: your seat is freed; your progress is kept until the match ends")},
                false, now_ms);
    s.quit = true;
    drop_connection(s, std::string(to_string(ErrorCode::idle)), now_ms);  // the error it was sent
  }
}

}  // namespace fts::protocol
