// A bot's script (--script): its steps run in order, each until it is done.
#include <algorithm>
#include <cmath>

#include "bot/bot.hpp"

namespace fts::bot {

void Bot::run_script(std::uint64_t now_ms) {
  while (script_.pc < options_.script.size() && !finished_) {
    const Step& s = options_.script[script_.pc];
    if (!script_.step_started) {
      script_.step_started = true;
      script_.command_sent = false;
      script_.step_deadline_ms = now_ms + static_cast<std::uint64_t>(script_.timeout_s * 1000);
      script_.step_until_tick = (latest_ ? latest_->tick : 0) + static_cast<std::uint32_t>(std::max(0.0, s.number));
    }
    if (!step_script(s, now_ms)) {
      if (!finished_ && now_ms > script_.step_deadline_ms)
        fail("script line " + std::to_string(s.line) + " '" + s.text + "': no success within " +
             std::to_string(static_cast<int>(script_.timeout_s)) + " s");
      return;
    }
    ++script_.pc;
    script_.step_started = false;
  }
  if (script_.pc >= options_.script.size()) finished_ = true;
}

bool Bot::step_script(const Step& s, std::uint64_t now_ms) {
  const bool connected = conn_.endpoint().state() == protocol::ClientState::connected;
  const std::uint32_t tick = latest_ ? latest_->tick : 0;
  switch (s.op) {
    case Step::Op::set_timeout: script_.timeout_s = s.number; return true;
    case Step::Op::wait_event:
      if (s.word == "connected") return connected && latest_.has_value();
      return std::find(new_events_.begin(), new_events_.end(), s.word) != new_events_.end();
    case Step::Op::wait_phase: return latest_ && s.word == phase_name(latest_->phase);
    case Step::Op::wait_ticks: return latest_ && tick >= script_.step_until_tick;
    case Step::Op::move: {
      script_.hunting = false;
      script_.hold = {};
      if (s.word == "left") script_.hold.move_x = -1;
      if (s.word == "right") script_.hold.move_x = 1;
      if (s.word == "up") script_.hold.move_y = 1;
      if (s.word == "down") script_.hold.move_y = -1;
      if (tick < script_.step_until_tick) return false;
      script_.hold = {};
      return true;
    }
    case Step::Op::hunt:
      if (s.number < 0) {
        script_.hunting = true;
        return true;
      }
      script_.hunting = tick < script_.step_until_tick;
      return !script_.hunting;
    case Step::Op::fire: script_.fire_once = true; return true;
    case Step::Op::buy:
    case Step::Op::ready:
    case Step::Op::play_again:
      if (!connected) return false;
      if (!script_.command_sent) {
        const auto op = s.op == Step::Op::buy ? protocol::CommandOp::buy
                        : s.op == Step::Op::ready ? protocol::CommandOp::ready : protocol::CommandOp::play_again;
        send_command(op, s.op == Step::Op::buy ? s.word[0] : 0, now_ms);
        script_.command_sent = true;
        return false;
      }
      return pending_rid_ == 0;
    case Step::Op::expect_result: {
      const bool ok = last_result_ && last_result_->ok;
      if ((s.word == "ok") != ok)
        fail("script line " + std::to_string(s.line) + " '" + s.text + "' failed: last result was " +
             (last_result_ ? (last_result_->ok ? "ok" : "refused (" + last_result_->code + ": " + last_result_->message + ")")
                           : std::string("none")));
      return true;
    }
    case Step::Op::expect_field: {
      // Judge on a snapshot newer than the step's start, so results are visible.
      if (!latest_ || latest_->tick < script_.step_until_tick + ticks_per_snapshot_) return false;
      const double v = field(s.word);
      if (!compare(v, s.cmp, s.number))
        fail("script line " + std::to_string(s.line) + " '" + s.text + "' failed: " + s.word + " is " +
             (std::isnan(v) ? std::string("unknown") : std::to_string(static_cast<long long>(v))));
      return true;
    }
    case Step::Op::expect_room: {
      if (s.word == "refused") return false;  // met (or failed) by the refusal in update()
      if (!connected) return false;
      const std::string code = room();
      if ((s.word == "any" && code.empty()) || (s.word != "any" && code != s.word))
        fail("script line " + std::to_string(s.line) + " '" + s.text + "' failed: the room is " +
             (code.empty() ? std::string("none") : code));
      return true;
    }
    case Step::Op::disconnect:
      script_.disconnected = true;
      conn_.leave(now_ms, "script");
      return true;
    case Step::Op::reconnect:
      if (!script_.reconnect_started) {
        script_.reconnect_started = true;
        script_.disconnected = false;
        latest_.reset();
        conn_.connect(now_ms);  // with the token of the last welcome
        return false;
      }
      if (connected && latest_) {
        script_.reconnect_started = false;
        return true;
      }
      return false;
  }
  return false;
}

}  // namespace fts::bot
