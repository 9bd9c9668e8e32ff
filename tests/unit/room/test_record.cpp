// The match record: written by RecordWriter, read back line by line by replay_record.
#include <catch2/catch.hpp>

#include <sstream>

#include "fts/room/record.hpp"

using namespace fts;

namespace {

// A recorded match: players with the given names join at tick 0, get ready, then move
// for `ticks` ticks; every tick goes through the writer as the server's host does it.
std::stringstream record_of(const std::vector<std::string>& names, int ticks) {
  std::stringstream out;
  const sim::MatchConfig cfg;
  room::RecordWriter w(out, 3, cfg, "test");
  auto s = sim::make_match(cfg, 3);
  for (int i = 0; i < ticks; ++i) {
    sim::TickInputs in;
    for (std::uint32_t p = 1; p <= names.size(); ++p) {
      if (i == 0) in.joins.push_back({p, names[p - 1]});
      sim::PlayerTick t;
      t.player = p;
      t.input.move_x = static_cast<std::int8_t>(i % 40 < 20 ? 1 : -1);
      if (i == 1) t.commands.push_back({sim::CommandKind::ready, {}});
      in.players.push_back(t);
    }
    w.inputs(s.tick, in);
    sim::step(s, in);
    w.stepped(s);
  }
  return out;
}

}  // namespace

TEST_CASE("Replay: a player named hash does not make the record unreplayable", "[room][replay]") {
  // Regression: a line was taken for a hash line when its text held "hash" anywhere, so
  // the join line of a player named hash failed the replay at line 2.
  auto record = record_of({"hash", "tick", "ann"}, 250);
  REQUIRE(record.str().find(R"("name":"hash")") != std::string::npos);
  auto r = room::replay_record(record);
  REQUIRE(std::holds_alternative<room::ReplayReport>(r));
  CHECK(std::get<room::ReplayReport>(r).hashes_checked == 2);
  CHECK(std::get<room::ReplayReport>(r).ticks == 250);
}

TEST_CASE("Replay: each line is dispatched on its keys", "[room][replay]") {
  const std::string head = record_of({}, 0).str();
  auto error_of = [&](const std::string& line) {
    std::stringstream in(head + line + "\n");
    auto r = room::replay_record(in);
    return std::holds_alternative<std::string>(r) ? std::get<std::string>(r) : std::string("ok");
  };
  CHECK(error_of(R"({"tick":3,"joins":[{"player":1,"name":"hash"}]})") == "ok");
  // A key twice is refused, not read as its last one (issue 36 point 9).
  CHECK(error_of(R"({"tick":3,"joins":[{"player":1,"name":"ann","player":2}]})") ==
        R"(line 2: invalid JSON: key "player" appears twice in one object (at joins[0].player))");
  CHECK(error_of(R"({"tick":100,"hash":"0000000000000000","joins":[]})") ==
        "line 2: a hash line needs an integer tick and a string hash, and nothing else");
  CHECK(error_of(R"({"tick":100,"hash":7})") ==
        "line 2: a hash line needs an integer tick and a string hash, and nothing else");
  CHECK(error_of(R"({"tick":100,"hash":"0000000000000000"})").rfind("line 2: hash mismatch at tick 100", 0) == 0);
  CHECK(error_of(R"({"tick":3,"hashes":1})") == R"(line 2: input line: hashes: unknown key (value 1))");
  CHECK(error_of(R"([1,2])").rfind("line 2: input line: ", 0) == 0);
  CHECK(error_of("{\"tick\":").rfind("line 2: invalid JSON: ", 0) == 0);
}
