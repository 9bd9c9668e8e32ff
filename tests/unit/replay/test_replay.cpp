// fts-client --replay's core: a record played back by common's match lands on the same
// state (hashes checked), seeks by level, plays at a chosen speed and pauses.
#include <catch2/catch.hpp>

#include <sstream>

#include "fts/room/record.hpp"
#include "replay/replay.hpp"

using namespace fts;
using fts::client::Replay;
using fts::client::Tape;

namespace {

// Two players join, get ready and push right then left; `ticks` ticks are recorded.
std::stringstream record_of(int ticks, sim::MatchState& end) {
  std::stringstream out;
  const sim::MatchConfig cfg;
  room::RecordWriter w(out, 11, cfg, "test");
  auto s = sim::make_match(cfg, 11);
  for (int i = 0; i < ticks; ++i) {
    sim::TickInputs in;
    for (std::uint32_t p = 1; p <= 2; ++p) {
      if (i == 0) in.joins.push_back({p, p == 1 ? "ann" : "bob"});
      sim::PlayerTick t;
      t.player = p;
      t.input.move_x = static_cast<std::int8_t>(i % 300 < 150 ? 1 : -1);
      t.input.move_y = static_cast<std::int8_t>(p == 1 ? 1 : -1);
      if (i == 1) t.commands.push_back({sim::CommandKind::ready, {}});
      in.players.push_back(t);
    }
    w.inputs(s.tick, in);
    sim::step(s, in);
    w.stepped(s);
  }
  end = s;
  return out;
}

Tape tape_of(std::stringstream& in) {
  auto t = client::load_tape(in);
  REQUIRE(std::holds_alternative<Tape>(t));
  return std::get<Tape>(std::move(t));
}

}  // namespace

TEST_CASE("a replay runs the record to the same state, hashes checked", "[client][replay]") {
  sim::MatchState live;
  auto rec = record_of(1200, live);
  Replay r(tape_of(rec));
  CHECK(r.tape().hashes.size() == 12);
  CHECK(r.tape().last_tick == 1200);
  r.run_to(1'000'000);  // clamped to the record's end
  CHECK(r.at_end());
  CHECK(r.mismatch().empty());
  CHECK(sim::match_hash(r.state()) == sim::match_hash(live));
  const auto snap = r.snapshot();
  REQUIRE(snap.players.size() == 2);
  CHECK(snap.players[0].name == "ann");
  CHECK(snap.players[0].coins == live.players[0].eco.coins);
  CHECK(snap.level == static_cast<std::uint32_t>(live.level));
}

TEST_CASE("a replay plays at its speed, pauses and seeks by level", "[client][replay]") {
  sim::MatchState live;
  auto rec = record_of(1200, live);
  Replay r(tape_of(rec));
  CHECK(r.speed() == 1);
  r.advance(500);  // 0.5 s at x1, 100 ticks a second
  CHECK(r.state().tick == 50);
  r.faster();
  r.faster();
  CHECK(r.speed() == 4);
  r.advance(250);
  CHECK(r.state().tick == 150);
  for (int i = 0; i < 10; ++i) r.faster();
  CHECK(r.speed() == 8);
  for (int i = 0; i < 10; ++i) r.slower();
  CHECK(r.speed() == 0.5);
  r.advance(30);  // 1.5 ticks: one now, the half carried
  r.advance(10);
  CHECK(r.state().tick == 152);
  r.toggle_pause();
  r.advance(10'000);
  CHECK(r.state().tick == 152);
  r.toggle_pause();
  // Level 1 starts once both are ready; seeking back to it starts from the beginning.
  r.seek_level(1);
  CHECK(r.state().level == 1);
  CHECK(r.state().phase == sim::Phase::playing);
  const auto start = r.state().tick;
  r.run_to(900);
  r.seek_level(1);
  CHECK(r.state().tick == start);
  CHECK(r.take_events().empty());  // a seek does not flood the log
  r.seek_level(99);  // never reached: the end
  CHECK(r.at_end());
  CHECK(r.mismatch().empty());
}

TEST_CASE("a damaged record is refused with the line", "[client][replay]") {
  sim::MatchState live;
  const std::string head = record_of(0, live).str();
  auto error_of = [&](const std::string& more) {
    std::stringstream in(head + more);
    auto t = client::load_tape(in);
    return std::holds_alternative<std::string>(t) ? std::get<std::string>(t) : std::string("ok");
  };
  CHECK(error_of("") == "ok");
  CHECK(error_of("{\"tick\":").rfind("line 2: invalid JSON", 0) == 0);
  CHECK(error_of("{\"tick\":5,\"joins\":[]}\n{\"tick\":3,\"joins\":[]}\n") == "line 3: tick 3 goes back in time");
  std::stringstream empty;
  CHECK(std::get<std::string>(client::load_tape(empty)) == "the record is empty");
  std::stringstream not_a_record("{\"hello\":1}\n");
  CHECK(std::get<std::string>(client::load_tape(not_a_record)).rfind("line 1: not a record header", 0) == 0);
  // A hash that differs is reported, the replay goes on.
  std::stringstream bad(head + "{\"tick\":10,\"hash\":\"0000000000000000\"}\n");
  Replay r(std::get<Tape>(client::load_tape(bad)));
  r.run_to(10);
  CHECK(r.mismatch().rfind("tick 10: recorded 0000000000000000, replayed ", 0) == 0);
}

// Issue 26 (8): the footer was 111-118 characters even with its spaces squeezed, so a
// 100-column terminal cut it (and "q: quit" with it).
TEST_CASE("the replay footer fits the terminal and keeps quit", "[client][replay]") {
  sim::MatchState live;
  auto rec = record_of(1200, live);
  Tape tape = tape_of(rec);
  tape.last_tick = 360'000;  // an hour's record: the longest position text
  Replay r(std::move(tape));
  r.run_to(1000);
  r.toggle_pause();
  r.slower();  // x0.5
  CHECK(client::replay_footer(r, 200) ==
        "Replay: tick 1000/360000 x0.5 (paused)   q: quit   Space: pause   -/+: speed   n/p: next/previous level"
        "   1-9: level   Tab: follow   e: end");
  for (const int cols : {60, 70, 80, 90, 100, 110, 120, 140}) {
    INFO(cols);
    const std::string footer = client::replay_footer(r, cols);
    INFO(footer);
    CHECK(static_cast<int>(footer.size()) <= cols);
    CHECK(footer.find("1000/360000 x0.5 (paused)") != std::string::npos);
    CHECK((footer.find("q: quit") != std::string::npos || footer.find("q quit") != std::string::npos));
    CHECK((footer.find("Space") != std::string::npos || footer.find("Spc") != std::string::npos));
  }
  // At 100 columns every key is still there, in short.
  const std::string at100 = client::replay_footer(r, 100);
  for (const char* key : {"q quit", "Spc pause", "-/+ speed", "n/p level", "1-9 lvl", "Tab follow", "e end"}) {
    INFO(key << " in " << at100);
    CHECK(at100.find(key) != std::string::npos);
  }
}

// Issue 37: after a seek (`9`, `n`) the log still said "Level 1 started.". The log and
// the score book follow the replay's position.
TEST_CASE("after a seek the replay's log is the position's", "[client][replay]") {
  sim::MatchState live;
  auto rec = record_of(1200, live);
  Replay r(tape_of(rec));
  client::ViewState view;
  const auto last_line = [&] { return view.messages.empty() ? std::string() : view.messages.back().text; };
  const auto has = [&](const std::string& text) {
    for (const auto& m : view.messages)
      if (m.text == text) return true;
    return false;
  };
  r.seek_level(1);
  client::replay_log(r, r.snapshot(), view, 1000);
  CHECK(last_line() == "Level 1 started.");
  // Play on: whatever happens after the start is logged as it comes.
  r.run_to(1200);
  client::replay_log(r, r.snapshot(), view, 2000);
  const auto later = view.messages;
  REQUIRE(later.size() >= 2);
  CHECK(later.back().text != "Level 1 started.");
  // Back to level 1: the log is the log at level 1's start, nothing from later.
  view.messages.push_back(client::LogLine{"a line from before the seek", 2500});
  r.seek_level(1);
  client::replay_log(r, r.snapshot(), view, 3000);
  CHECK(last_line() == "Level 1 started.");
  CHECK_FALSE(has("a line from before the seek"));
  CHECK_FALSE(has(later.back().text));
  // To the end (`9` in a record that never reaches level 9): the end's lines.
  r.seek_level(9);
  client::replay_log(r, r.snapshot(), view, 4000);
  CHECK(last_line() == later.back().text);
  CHECK(view.scores == r.scores());
}
