// Every way a journal can be cut or garbled at --resume (issue 30): whatever the damage,
// read_journal either resumes the room at a tick the match really had (its hash and
// event number those of the live run) or refuses it with a message naming each segment;
// it never crashes and never resumes a state that never existed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <string>

#include "journal_fixture.hpp"

using namespace fts;
using namespace fts::test;
namespace fs = std::filesystem;

namespace {

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// The room read back is one the live run went through.
void check_real(const Played& p, const store::ResumedRoom& r, const std::string& what) {
  INFO(what << ": resumed at tick " << r.state.tick << ", damage \"" << r.damage << "\"");
  REQUIRE(p.hash_at.count(r.state.tick) == 1);
  CHECK(sim::match_hash(r.state) == p.hash_at.at(r.state.tick));
  CHECK(r.event_seq == p.seq_at.at(r.state.tick));
  CHECK(r.sessions.size() == 2);
}

// A room of two segments (checkpoints at ticks 200 and 400), 445 ticks played (the last
// five after the last hash line, at 440).
struct TwoSegments {
  TempDir d;
  Played p;
  fs::path older, newest;
  std::string bytes;  // the newest segment as written
  TwoSegments() {
    {
      store::JournalWriter w(config_in(d.path, 200), p.cfg, p.state, 0, {});
      p.play(w, 445);
    }
    const auto segs = store::list_segments(d.path);
    REQUIRE(segs.size() == 2);
    older = segs.front().second;
    newest = segs.back().second;
    bytes = read_bytes(newest);
  }
};

}  // namespace

TEST_CASE("Journal cuts: cut anywhere, the room resumes at a tick it really had, never later for less", "[journal]") {
  TwoSegments t;
  // Every cut at and around each line's end, and an even spread of cuts in between.
  std::set<std::size_t> cuts = {0, t.bytes.size()};
  for (std::size_t at = t.bytes.find('\n'); at != std::string::npos; at = t.bytes.find('\n', at + 1))
    for (std::size_t c = at > 2 ? at - 2 : 0; c <= std::min(at + 2, t.bytes.size()); ++c) cuts.insert(c);
  for (std::size_t c = 0; c < t.bytes.size(); c += t.bytes.size() / 150 + 1) cuts.insert(c);
  std::int64_t last_tick = -1;
  for (const std::size_t cut : cuts) {
    write_bytes(t.newest, t.bytes.substr(0, cut));
    const auto r = read_ok(t.d.path);
    check_real(t.p, r, "cut at byte " + std::to_string(cut) + " of " + std::to_string(t.bytes.size()));
    CHECK(r.state.tick >= 400);  // the older segment's checkpoint, replayed to its end, reaches 400
    CHECK(r.state.tick >= last_tick);  // a longer file never resumes earlier
    last_tick = r.state.tick;
    // A cut inside a line is noticed (a cut at a line's end reads as a shorter run).
    if (cut == 0 || t.bytes[cut - 1] != '\n') CHECK((!r.damage.empty() || !r.skipped.empty()));
  }
  CHECK(last_tick == 445);
}

TEST_CASE("Journal cuts: a garbled byte in any line resumes at a real tick or falls back", "[journal]") {
  TwoSegments t;
  const char garbles[] = {'\0', '\xff', '}', '7'};
  std::size_t line_start = 0, lines = 0;
  while (line_start < t.bytes.size()) {
    const std::size_t end = std::min(t.bytes.find('\n', line_start), t.bytes.size());
    // The line's first, middle and last byte, each replaced by each garble.
    for (const std::size_t at : {line_start, line_start + (end - line_start) / 2, end > line_start ? end - 1 : end}) {
      for (const char g : garbles) {
        std::string bad = t.bytes;
        if (bad[at] == g) continue;
        bad[at] = g;
        write_bytes(t.newest, bad);
        const auto r = read_ok(t.d.path);
        check_real(t.p, r, "line " + std::to_string(lines + 1) + " byte " + std::to_string(at) + " set to " +
                               std::to_string(static_cast<unsigned char>(g)));
        CHECK(r.state.tick >= 400);
      }
    }
    line_start = end + 1;
    ++lines;
  }
  CHECK(lines > 20);
}

TEST_CASE("Journal cuts: both segments garbled, the room is refused with each segment's reason", "[journal]") {
  TwoSegments t;
  for (const fs::path& seg : {t.older, t.newest}) {
    std::string bad = read_bytes(seg);
    bad[bad.find('\n') / 2] = '\0';  // the header
    write_bytes(seg, bad);
  }
  const auto r = store::read_journal(t.d.path);
  REQUIRE(std::holds_alternative<std::string>(r));
  const std::string& why = std::get<std::string>(r);
  CHECK_THAT(why, Catch::Contains("no usable journal segment"));
  CHECK_THAT(why, Catch::Contains(t.older.filename().string()));
  CHECK_THAT(why, Catch::Contains(t.newest.filename().string()));

  // Cut to nothing, both: refused the same way.
  write_bytes(t.older, "");
  write_bytes(t.newest, "");
  const auto empty = store::read_journal(t.d.path);
  REQUIRE(std::holds_alternative<std::string>(empty));
  CHECK_THAT(std::get<std::string>(empty), Catch::Contains("no usable journal segment"));
}

// Issue 36 point 9: a line with a key twice was read as its last one; now it is damage.
TEST_CASE("Journal cuts: a line with a key twice is damage, named, never read as its last key", "[journal]") {
  TwoSegments t;
  // A hash line late in the newest segment gets its tick a second time.
  const std::size_t at = t.bytes.rfind(R"({"tick":440,"hash")");
  REQUIRE(at != std::string::npos);
  std::string bad = t.bytes;
  bad.insert(at + 1, R"("tick":1,)");
  write_bytes(t.newest, bad);
  auto r = read_ok(t.d.path);
  check_real(t.p, r, "a hash line with tick twice");
  CHECK(r.state.tick <= 440);  // stopped there: the file goes on to 445
  CHECK_THAT(r.damage, Catch::Contains(R"(invalid JSON (key "tick" appears twice in one object))"));
  // The checkpoint's header line with a key twice: the segment is skipped, the older used.
  bad = t.bytes;
  bad.insert(1, R"("room":"ZZZZ",)");
  write_bytes(t.newest, bad);
  r = read_ok(t.d.path);
  check_real(t.p, r, "a header with room twice");
  REQUIRE(r.skipped.size() == 1);
  CHECK_THAT(r.skipped[0], Catch::Contains(R"(line 1: invalid JSON: key "room" appears twice in one object)"));
}
