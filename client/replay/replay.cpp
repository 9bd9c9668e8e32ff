#include "replay/replay.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "app/snapshot_build.hpp"
#include "fts/sim/match_view.hpp"
#include "host/json_fields.hpp"
#include "host/match_config_json.hpp"
#include "host/text.hpp"
#include "ui/panel.hpp"

namespace fts::client {

namespace {
constexpr std::size_t kRecentEvents = 64;  // as many as a snapshot carries at most
constexpr std::int64_t kMaxGapTicks = 10'000'000;  // a damaged file, not hours of empty ticks
}  // namespace

std::variant<Tape, std::string> load_tape(std::istream& in, std::size_t max_lines) {
  std::string line;
  if (!std::getline(in, line)) return std::string("the record is empty");
  std::string why;
  auto head = host::parse_json(line, why);
  if (!head) return "line 1: not a record header: " + why;
  if (!head->is_object() || !head->contains("fts_record") || !head->contains("seed") || !head->contains("config"))
    return std::string("line 1: not a record header (needs fts_record, seed, config)");
  if (!(*head)["seed"].is_number_unsigned()) return std::string("line 1: seed must be a non-negative integer");
  auto cfg = host::parse_match_config((*head)["config"].dump());
  if (auto* err = std::get_if<std::string>(&cfg)) return "line 1: config: " + *err;
  Tape t;
  t.seed = (*head)["seed"].get<std::uint64_t>();
  t.config = std::get<sim::MatchConfig>(cfg);
  for (std::size_t no = 2; std::getline(in, line); ++no) {
    if (line.empty()) continue;
    if (no > max_lines) return "the record has more than " + std::to_string(max_lines) + " lines";
    const std::string where = "line " + std::to_string(no) + ": ";
    auto j = host::parse_json(line, why);
    if (!j) return where + "invalid JSON: " + why;
    std::int64_t tick = 0;
    if (j->is_object() && j->contains("hash")) {
      if (!(*j)["tick"].is_number_integer() || !(*j)["hash"].is_string())
        return where + "a hash line needs an integer tick and a string hash";
      tick = (*j)["tick"].get<std::int64_t>();
      if (tick < t.last_tick) return where + "tick " + std::to_string(tick) + " goes back in time";
      t.hashes.emplace_back(tick, (*j)["hash"].get<std::string>());
    } else {
      auto parsed = host::input_line_from_json(*j);
      if (auto* err = std::get_if<std::string>(&parsed)) return where + *err;
      auto& il = std::get<host::InputLine>(parsed);
      tick = il.tick;
      if (tick < t.last_tick) return where + "tick " + std::to_string(tick) + " goes back in time";
      t.lines.push_back({il.tick, std::move(il.inputs)});
    }
    if (tick - t.last_tick > kMaxGapTicks) return where + "tick " + std::to_string(tick) + " is too far ahead";
    t.last_tick = std::max(t.last_tick, tick + (j->contains("hash") ? 0 : 1));
  }
  return t;
}

Replay::Replay(Tape tape) : tape_(std::move(tape)) { restart(); }

void Replay::restart() {
  state_ = sim::make_match(tape_.config, tape_.seed);
  next_line_ = 0;
  next_hash_ = 0;
  carry_ticks_ = 0;
  recent_.clear();
  fresh_.clear();
  event_seq_ = 0;
}

void Replay::step_once() {
  sim::TickInputs none;
  const sim::TickInputs* in = &none;
  while (next_line_ < tape_.lines.size() && tape_.lines[next_line_].tick < state_.tick) ++next_line_;
  if (next_line_ < tape_.lines.size() && tape_.lines[next_line_].tick == state_.tick) in = &tape_.lines[next_line_++].inputs;
  const std::int64_t tick = state_.tick;
  const sim::TickOutput out = sim::step(state_, *in);
  std::vector<protocol::Event> wire;
  server::append_wire_events(tick, out.events, wire);
  for (auto& e : wire) {
    e.seq = ++event_seq_;
    recent_.push_back(e);
    fresh_.push_back(e);
  }
  while (recent_.size() > kRecentEvents) recent_.pop_front();
  if (fresh_.size() > 4 * kRecentEvents) fresh_.erase(fresh_.begin(), fresh_.end() - kRecentEvents);
  while (next_hash_ < tape_.hashes.size() && tape_.hashes[next_hash_].first <= state_.tick) {
    const auto& [at, want] = tape_.hashes[next_hash_++];
    if (at != state_.tick || !mismatch_.empty()) continue;
    const std::string got = host::hex16(sim::match_hash(state_));
    if (got != want) mismatch_ = "tick " + std::to_string(at) + ": recorded " + want + ", replayed " + got;
  }
}

void Replay::run_to(std::int64_t tick) {
  tick = std::min(tick, tape_.last_tick);
  while (state_.tick < tick) step_once();
}

void Replay::seek_level(std::int64_t level) {
  if (level <= 0) level = 1;
  if (state_.level >= level) restart();
  while (!at_end() && !(state_.level >= level && state_.phase == sim::Phase::playing)) step_once();
  fresh_.clear();  // a seek does not flood the log
  carry_ticks_ = 0;
}

void Replay::advance(std::uint64_t elapsed_ms) {
  if (paused_ || at_end()) return;
  carry_ticks_ += static_cast<double>(elapsed_ms) / 1000.0 * tape_.config.tick_rate_hz * speed();
  const auto whole = static_cast<std::int64_t>(carry_ticks_);
  carry_ticks_ -= static_cast<double>(whole);
  run_to(state_.tick + whole);
}

protocol::Snapshot Replay::snapshot() const { return server::build_snapshot(sim::make_view(state_), recent_); }

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
