#include "replay/replay.hpp"

#include <algorithm>
#include <cstdio>
#include <iterator>

#include "fts/room/text.hpp"
#include "ui/hud.hpp"
#include "ui/panel.hpp"

namespace fts::client {

Replay::Replay(Tape tape) : tape_(std::move(tape)) { restart(); }

void Replay::restart() {
  room_ = room::RoomStepper(tape_.config, tape_.seed);
  next_line_ = 0;
  next_hash_ = 0;
  carry_ticks_ = 0;
  fresh_.clear();
  recent_.clear();
  scores_.clear();
}

void Replay::step_once() {
  const sim::MatchState& state = room_.match();
  sim::TickInputs none;
  const sim::TickInputs* in = &none;
  while (next_line_ < tape_.lines.size() && tape_.lines[next_line_].tick < state.tick) ++next_line_;
  if (next_line_ < tape_.lines.size() && tape_.lines[next_line_].tick == state.tick) in = &tape_.lines[next_line_++].inputs;
  const std::size_t before = fresh_.size();
  room_.step(*in, &fresh_);
  for (std::size_t i = before; i < fresh_.size(); ++i) {
    tally_event(scores_, fresh_[i]);
    recent_.push_back(fresh_[i]);
    if (recent_.size() > kLogKeep) recent_.pop_front();
  }
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
  fresh_.clear();  // a seek does not flood the log: replay_log shows the position's last lines
  carry_ticks_ = 0;
  seeked_ = true;
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

void replay_log(Replay& r, const protocol::Snapshot& snap, ViewState& view, std::uint64_t now_ms) {
  const auto note = [&](std::string text) {
    view.messages.push_back(LogLine{std::move(text), now_ms});
    if (view.messages.size() > kLogKeep) view.messages.erase(view.messages.begin());
  };
  std::vector<protocol::Event> events = r.take_events();
  if (r.take_seeked()) {
    view.messages.clear();
    events.assign(r.recent().begin(), r.recent().end());
  }
  view.scores = r.scores();
  for (const auto& e : events)
    if (std::string line = describe_event(e, snap, 0, &view.names); !line.empty()) note(std::move(line));
  for (const auto& p : snap.players) view.names[p.id] = p.name;
}

namespace {

// The replay's keys, most needed first; each in words and in short.
struct FooterKey {
  const char* words;
  const char* brief;
};
constexpr FooterKey kReplayKeys[] = {
    {"q: quit", "q quit"},       {"Space: pause", "Spc pause"},
    {"-/+: speed", "-/+ speed"}, {"n/p: next/previous level", "n/p level"},
    {"1-9: level", "1-9 lvl"},   {"Tab: follow", "Tab follow"},
    {"e: end", "e end"},
};

}  // namespace

std::string replay_footer(const Replay& r, int cols) {
  char speed[16];
  std::snprintf(speed, sizeof speed, "x%g", r.speed());
  const std::string where = std::to_string(r.state().tick) + "/" + std::to_string(r.tape().last_tick) + " " + speed +
                            (r.at_end() ? " (end)" : r.paused() ? " (paused)" : "");
  // Shortened until it fits: the keys' spacing, their words, the "Replay: tick" words,
  // then the least needed keys (quit stays, "Replay" comes back); at last cut.
  const auto compose = [&](const std::string& head, bool brief, const char* gap, std::size_t keys) {
    std::string text = head + where;
    std::size_t n = 0;
    for (const FooterKey& k : kReplayKeys) {
      if (n++ == keys) break;
      text += gap;
      text += brief ? k.brief : k.words;
    }
    return text;
  };
  const std::size_t all = std::size(kReplayKeys);
  const std::string tries[] = {compose("Replay: tick ", false, "   ", all), compose("Replay: tick ", false, "  ", all),
                               compose("Replay: tick ", true, "  ", all), compose("Replay ", true, "  ", all),
                               compose("", true, "  ", all)};
  for (const auto& text : tries)
    if (std::ssize(text) <= cols) return text;
  for (std::size_t keys = all; keys-- > 1;)
    if (const std::string text = compose("Replay ", true, "  ", keys); std::ssize(text) <= cols) return text;
  return compose("", true, " ", 1).substr(0, static_cast<std::size_t>(std::max(cols, 0)));
}

}  // namespace fts::client
