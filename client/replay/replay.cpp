#include "replay/replay.hpp"

#include <algorithm>

#include "fts/room/text.hpp"
#include "ui/panel.hpp"

namespace fts::client {

Replay::Replay(Tape tape) : tape_(std::move(tape)) { restart(); }

void Replay::restart() {
  room_ = room::RoomStepper(tape_.config, tape_.seed);
  next_line_ = 0;
  next_hash_ = 0;
  carry_ticks_ = 0;
  fresh_.clear();
}

void Replay::step_once() {
  const sim::MatchState& state = room_.match();
  sim::TickInputs none;
  const sim::TickInputs* in = &none;
  while (next_line_ < tape_.lines.size() && tape_.lines[next_line_].tick < state.tick) ++next_line_;
  if (next_line_ < tape_.lines.size() && tape_.lines[next_line_].tick == state.tick) in = &tape_.lines[next_line_++].inputs;
  room_.step(*in, &fresh_);
  if (fresh_.size() > 4 * room::kRecentEvents) fresh_.erase(fresh_.begin(), fresh_.end() - room::kRecentEvents);
  while (next_hash_ < tape_.hashes.size() && tape_.hashes[next_hash_].tick <= state.tick) {
    const room::TapeHash& h = tape_.hashes[next_hash_++];
    if (h.tick != state.tick || !mismatch_.empty()) continue;
    const std::string got = room::hex16(sim::match_hash(state));
    if (got != h.hex) mismatch_ = "tick " + std::to_string(h.tick) + ": recorded " + h.hex + ", replayed " + got;
  }
}

void Replay::run_to(std::int64_t tick) {
  tick = std::min(tick, tape_.last_tick);
  while (state().tick < tick) step_once();
}

void Replay::seek_level(std::int64_t level) {
  if (level <= 0) level = 1;
  if (state().level >= level) restart();
  while (!at_end() && !(state().level >= level && state().phase == sim::Phase::playing)) step_once();
  fresh_.clear();  // a seek does not flood the log
  carry_ticks_ = 0;
}

void Replay::advance(std::uint64_t elapsed_ms) {
  if (paused_ || at_end()) return;
  carry_ticks_ += static_cast<double>(elapsed_ms) / 1000.0 * tape_.config.tick_rate_hz * speed();
  const auto whole = static_cast<std::int64_t>(carry_ticks_);
  carry_ticks_ -= static_cast<double>(whole);
  run_to(state().tick + whole);
}

protocol::Snapshot Replay::snapshot() const { return room_.snapshot(); }

std::vector<protocol::Event> Replay::take_events() { return std::exchange(fresh_, {}); }

std::string replay_footer(const Replay& r, int cols) {
  char speed[16];
  std::snprintf(speed, sizeof speed, "x%g", r.speed());
  std::string text = "Replay: tick " + std::to_string(r.state().tick) + "/" + std::to_string(r.tape().last_tick) + " " +
                     speed + (r.at_end() ? " (end)" : r.paused() ? " (paused)" : "") +
                     "   Space: pause   -/+: speed   n/p: next/previous level   1-9: level   Tab: follow   q: quit";
  return fit_footer(std::move(text), cols);
}

}  // namespace fts::client
