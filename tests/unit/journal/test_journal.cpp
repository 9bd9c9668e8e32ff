// The room journal (server/store/journal.hpp): written by JournalWriter as the host does
// it, read back by read_journal; damaged journals resume to their last good tick.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>
#include <chrono>

#include "store/journal.hpp"
#include "journal_fixture.hpp"
#include "store/match_state_json.hpp"
#include "fts/room/snapshot_build.hpp"
#include "fts/room/text.hpp"

using namespace fts;
namespace fs = std::filesystem;

using namespace fts::test;

TEST_CASE("Journal: a match state survives JSON bit for bit", "[journal]") {
  Played p;
  TempDir d;
  store::JournalWriter w(config_in(d.path, 100000), p.cfg, p.state, 0, {});
  p.play(w, 700);
  const auto j = store::match_state_to_json(p.state);
  auto back = store::match_state_from_json(nlohmann::json::parse(j.dump()), sim::make_match(p.cfg, 7));
  REQUIRE(std::holds_alternative<sim::MatchState>(back));
  CHECK(sim::match_hash(std::get<sim::MatchState>(back)) == sim::match_hash(p.state));
  CHECK(!p.state.world.balls.empty());

  auto broken = j;
  broken["players"][0]["eco"] = "rich";
  auto bad = store::match_state_from_json(broken, sim::make_match(p.cfg, 7));
  REQUIRE(std::holds_alternative<std::string>(bad));
  CHECK(std::get<std::string>(bad) == "checkpoint: players: 0: eco: must be an array of 15 values");

  // The tables' messages name the path to a bad value (rows by their field's name).
  auto error_of = [&](auto edit) {
    auto k = j;
    edit(k);
    auto r = store::match_state_from_json(k, sim::make_match(p.cfg, 7));
    return std::holds_alternative<std::string>(r) ? std::get<std::string>(r) : std::string("read");
  };
  CHECK_THAT(error_of([](auto& k) { k["balls"][0][2] = "up"; }), Catch::StartsWith("checkpoint: balls: 0: y: "));
  CHECK(error_of([](auto& k) { k["balls"][0].erase(6); }) == "checkpoint: balls: 0: must be an array of 7 values");
  CHECK(error_of([](auto& k) { k["players"][1]["id"] = 1; }) == "checkpoint: players: 1: ids not ascending");
  CHECK(error_of([](auto& k) { k["phase"] = 9; }) == "checkpoint: phase: out of range, got 9");
  if (!p.state.bodies.empty()) {
    CHECK(error_of([](auto& k) { k["bodies"][0][1] = 7; }) == "checkpoint: bodies: 0: kind: out of range, got 7");
    CHECK(error_of([](auto& k) { k["bodies"].push_back(k["bodies"][0]); }) == "checkpoint: bodies: " + std::to_string(p.state.bodies.size()) + ": an id twice");
  }
}

TEST_CASE("Journal: round trip to the last tick, sessions and event numbers included", "[journal]") {
  TempDir d;
  Played p;
  {
    store::JournalWriter w(config_in(d.path, 250), p.cfg, p.state, 0, {});
    p.play(w, 1234);
    w.released(p.state.tick, 2);
    w.session(p.state.tick, {1, "ann", std::string(32, 'a'), true});
    w.flush();
    const auto st = w.stats();
    CHECK(st.error.empty());
    CHECK(st.dropped == 0);
    CHECK(st.durable_tick == p.state.tick);
    CHECK(st.segments == 5);  // ticks 0, 250, 500, 750, 1000
  }
  const auto r = read_ok(d.path);
  CHECK(r.damage.empty());
  CHECK(r.room == "main");
  CHECK(r.seed == 7);
  CHECK(r.state.tick == 1234);
  CHECK(sim::match_hash(r.state) == sim::match_hash(p.state));
  CHECK(r.event_seq == p.event_seq);
  CHECK(r.checkpoint_tick == 1000);
  CHECK(r.ticks_replayed == 234);
  CHECK(r.hashes_checked == 23);
  REQUIRE(r.sessions.size() == 1);
  CHECK(r.sessions[0] == store::JournalSession{1, "ann", std::string(32, 'a'), true});
  // Compaction: only the newest two segments are kept.
  const auto segs = store::list_segments(d.path);
  REQUIRE(segs.size() == 2);
  CHECK(segs[0].first == 4);
  CHECK(segs[1].first == 5);
}

TEST_CASE("Journal: checkpoint plus replay equals a straight replay", "[journal]") {
  TempDir straight, checkpoints;
  Played a, b;
  {
    store::JournalWriter w(config_in(straight.path, 1'000'000), a.cfg, a.state, 0, {});
    a.play(w, 2000);
  }
  {
    store::JournalWriter w(config_in(checkpoints.path, 170), b.cfg, b.state, 0, {});
    b.play(w, 2000);
  }
  const auto ra = read_ok(straight.path);
  const auto rb = read_ok(checkpoints.path);
  CHECK(ra.checkpoint_tick == 0);
  CHECK(ra.ticks_replayed == 2000);
  CHECK(rb.checkpoint_tick == 1870);
  CHECK(rb.ticks_replayed == 130);
  CHECK(sim::match_hash(ra.state) == sim::match_hash(rb.state));
  CHECK(sim::match_hash(ra.state) == a.hash_at.at(2000));
  CHECK(ra.event_seq == rb.event_seq);
}

TEST_CASE("Journal: a torn last line resumes to the line before it", "[journal]") {
  TempDir d;
  Played p;
  {
    store::JournalWriter w(config_in(d.path, 100000), p.cfg, p.state, 0, {});
    p.play(w, 345);
  }
  const fs::path file = store::list_segments(d.path).back().second;
  auto lines = lines_of(file);
  // The last complete input line is for tick 344; cut the line half way.
  std::string last = lines.back();
  REQUIRE(nlohmann::json::parse(last).at("tick") == 344);
  lines.back() = last.substr(0, last.size() / 2);
  write_lines(file, lines, false);
  const auto r = read_ok(d.path);
  CHECK_THAT(r.damage, Catch::Contains("torn"));
  CHECK(r.state.tick == 344);
  CHECK(sim::match_hash(r.state) == p.hash_at.at(344));
  CHECK(r.event_seq == p.seq_at.at(344));

  // Cut at the very end of a line (only the newline missing): still not trusted.
  lines.back() = last;
  write_lines(file, lines, false);
  CHECK(read_ok(d.path).state.tick == 344);
  write_lines(file, lines, true);
  CHECK(read_ok(d.path).state.tick == 345);
}

TEST_CASE("Journal: a hash that differs rolls back to the last hash that matched", "[journal]") {
  TempDir d;
  Played p;
  {
    store::JournalWriter w(config_in(d.path, 100000), p.cfg, p.state, 0, {});
    p.play(w, 500);
  }
  const fs::path file = store::list_segments(d.path).back().second;
  auto lines = lines_of(file);
  bool changed = false;
  for (auto& line : lines) {
    if (line.rfind(R"({"tick":300,"hash":")", 0) != 0) continue;
    const auto at = line.find("\"hash\":\"") + 8;
    line[at] = line[at] == '0' ? '1' : '0';
    changed = true;
  }
  REQUIRE(changed);
  write_lines(file, lines);
  const auto r = read_ok(d.path);
  CHECK_THAT(r.damage, Catch::Contains("hash mismatch at tick 300"));
  CHECK(r.state.tick == 290);
  CHECK(sim::match_hash(r.state) == p.hash_at.at(290));
  CHECK(r.event_seq == p.seq_at.at(290));
  CHECK(r.hashes_checked == 29);
}

TEST_CASE("Journal: a damaged newest checkpoint falls back to the segment before", "[journal]") {
  TempDir d;
  Played p;
  {
    store::JournalWriter w(config_in(d.path, 200), p.cfg, p.state, 0, {});
    p.play(w, 450);
  }
  auto segs = store::list_segments(d.path);
  REQUIRE(segs.size() == 2);  // ticks 200 and 400
  auto lines = lines_of(segs.back().second);
  lines[1] = lines[1].substr(0, 100);  // the checkpoint line torn
  write_lines(segs.back().second, {lines[0], lines[1]}, false);
  const auto r = read_ok(d.path);
  REQUIRE(r.skipped.size() == 1);
  CHECK_THAT(r.skipped[0], Catch::Contains("checkpoint"));
  CHECK(r.checkpoint_tick == 200);
  CHECK(r.state.tick == 400);
  CHECK(sim::match_hash(r.state) == p.hash_at.at(400));
}

TEST_CASE("Journal: nothing usable is reported, never a crash", "[journal]") {
  TempDir d;
  auto none = store::read_journal(d.path);
  REQUIRE(std::holds_alternative<std::string>(none));
  CHECK_THAT(std::get<std::string>(none), Catch::Contains("no journal segments"));

  write_lines(d.path / store::segment_name(1), {"{\"fts_journal\":1", "garbage"});
  write_lines(d.path / store::segment_name(2), {R"({"fts_journal":9,"room":"main"})", "{}"});
  write_lines(d.path / store::segment_name(3), {});
  auto bad = store::read_journal(d.path);
  REQUIRE(std::holds_alternative<std::string>(bad));
  const std::string& why = std::get<std::string>(bad);
  CHECK_THAT(why, Catch::Contains("no usable journal segment"));
  CHECK_THAT(why, Catch::Contains("journal-000001.jsonl: line 1: invalid JSON"));
  CHECK_THAT(why, Catch::Contains("journal-000002.jsonl: line 1: unknown journal format"));
  CHECK_THAT(why, Catch::Contains("journal-000003.jsonl: line 1: no complete header"));
}

TEST_CASE("Journal: a full queue drops records until a new checkpoint, and stays consistent", "[journal]") {
  TempDir d;
  Played p;
  auto cfg = config_in(d.path, 100000);
  cfg.max_queued = 8;
  cfg.sync_ms = 10000;  // the writer waits 10 s between syncs: the queue fills at once
  {
    store::JournalWriter w(cfg, p.cfg, p.state, 0, {});
    p.play(w, 100);
    CHECK(w.stats().dropped > 0);
  }
  // Whatever was kept is a prefix of the match: it replays to a tick the match passed.
  const auto r = read_ok(d.path);
  CHECK(r.state.tick <= 100);
  if (r.state.tick > 0) CHECK(sim::match_hash(r.state) == p.hash_at.at(r.state.tick));
}

TEST_CASE("Journal: a second writer on the same room directory is refused", "[journal]") {
  TempDir d;
  Played p;
  store::JournalWriter first(config_in(d.path, 1000), p.cfg, p.state, 0, {});
  store::JournalWriter second(config_in(d.path, 1000), p.cfg, p.state, 0, {});
  CHECK(first.stats().error.empty());
  CHECK_THAT(second.stats().error, Catch::Contains("in use by another process"));
  second.inputs(0, inputs_at(0));
  second.flush();  // returns at once
  first.flush();
  CHECK(store::list_segments(d.path).size() == 1);
}

TEST_CASE("Journal: finish writes what is queued, then removes the room's directory", "[journal]") {
  TempDir d;
  Played p;
  const fs::path room = d.path / "ABCDE";
  store::JournalWriter w(config_in(room, 1000), p.cfg, p.state, 0, {});
  p.play(w, 50);
  w.flush();
  REQUIRE(store::list_segments(room).size() == 1);
  w.finish();
  w.inputs(p.state.tick, inputs_at(p.state.tick));  // after finish: nothing is queued
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!w.stopped() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  REQUIRE(w.stopped());
  CHECK(w.stats().finished);
  CHECK(w.stats().error.empty());
  CHECK_FALSE(fs::exists(room));
  CHECK_FALSE(fs::exists(d.path / "ABCDE.closed"));
}
