// One history reader (issue 38): a journal that keeps every segment replays as a whole
// match, as a record of format 1 does, and each says which format it is.
#include <sstream>

#include "fts/room/record.hpp"
#include "journal_fixture.hpp"

using namespace fts;
using fts::test::Played;
using fts::test::TempDir;

namespace {

// A journal of `ticks` ticks with a segment every 100 ticks, every segment kept.
void journal_every_segment(const std::filesystem::path& dir, Played& p, std::int64_t ticks) {
  auto c = test::config_in(dir, 100);
  c.keep_segments = 1000;
  store::JournalWriter w(c, p.cfg, p.state, 0, {});
  p.play(w, ticks);
  w.flush();
}

}  // namespace

TEST_CASE("History: a journal that keeps every segment replays the whole match", "[journal][history]") {
  TempDir dir;
  Played p;
  journal_every_segment(dir.path, p, 450);
  REQUIRE(room::list_segments(dir.path).size() == 5);

  auto loaded = room::load_history(dir.path);
  if (auto* err = std::get_if<std::string>(&loaded)) FAIL(*err);
  const auto& tape = std::get<room::Tape>(loaded);
  CHECK(tape.format == "journal 1");
  CHECK(tape.seed == 7);
  // A hash line every 10 ticks, but where a segment starts: its checkpoint holds the hash.
  CHECK(tape.hashes.size() == 45 - 4 + 5);

  auto r = room::replay_history(dir.path);
  if (auto* err = std::get_if<std::string>(&r)) FAIL(*err);
  const auto& rep = std::get<room::ReplayReport>(r);
  CHECK(rep.format == "journal 1");
  CHECK(rep.ticks == 450);
  CHECK(rep.hashes_checked == 46);
  CHECK(rep.final_hash == p.hash_at.at(450));
}

TEST_CASE("History: a journal without its first segment is not a whole match", "[journal][history]") {
  TempDir dir;
  Played p;
  journal_every_segment(dir.path, p, 250);
  std::filesystem::remove(dir.path / room::segment_name(1));
  auto r = room::replay_history(dir.path);
  REQUIRE(std::holds_alternative<std::string>(r));
  CHECK_THAT(std::get<std::string>(r), Catch::Contains("starts at segment 2"));
}

TEST_CASE("History: a damaged line or a hash that differs is named by file and line", "[journal][history]") {
  TempDir dir;
  Played p;
  journal_every_segment(dir.path, p, 150);
  const auto file = dir.path / room::segment_name(1);
  const auto lines = test::lines_of(file);
  SECTION("a line that is not JSON") {
    auto bad = lines;
    bad[5] = "{not json";
    test::write_lines(file, bad);
    auto r = room::replay_history(dir.path);
    REQUIRE(std::holds_alternative<std::string>(r));
    CHECK_THAT(std::get<std::string>(r), Catch::Contains("journal-000001.jsonl line 6: invalid JSON"));
  }
  SECTION("a hash line's hash") {
    auto bad = lines;
    std::size_t at = 0;
    for (std::size_t i = 2; i < bad.size() && !at; ++i)
      if (const auto k = bad[i].find("\"hash\":\""); k != std::string::npos) {
        bad[i].replace(k + 8, 16, std::string(16, '0'));
        at = i;
      }
    REQUIRE(at > 0);
    test::write_lines(file, bad);
    auto r = room::replay_history(dir.path);
    REQUIRE(std::holds_alternative<std::string>(r));
    CHECK_THAT(std::get<std::string>(r),
               Catch::Contains("journal-000001.jsonl line " + std::to_string(at + 1) + ": hash mismatch"));
  }
}

TEST_CASE("History: a record of format 1 still replays and says so", "[journal][history]") {
  TempDir dir;
  const auto file = dir.path / "old-record.jsonl";
  sim::MatchConfig cfg;
  {
    std::ofstream out(file);
    room::RecordWriter w(out, 7, cfg, "test");
    sim::MatchState s = sim::make_match(cfg, 7);
    for (int i = 0; i < 250; ++i) {
      const auto in = test::inputs_at(s.tick);
      w.inputs(s.tick, in);
      sim::step(s, in);
      w.stepped(s);
    }
  }
  auto r = room::replay_history(file);
  if (auto* err = std::get_if<std::string>(&r)) FAIL(*err);
  CHECK(std::get<room::ReplayReport>(r).format == "record 1");
  CHECK(std::get<room::ReplayReport>(r).hashes_checked == 2);
}
