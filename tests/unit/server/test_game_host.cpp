// The server without its socket: real protocol clients against GameHost in memory, time
// stepped by hand.
#include <catch2/catch.hpp>

#include <sstream>

#include "app/game_host.hpp"
#include "../../support/host_rig.hpp"
#include "fts/protocol/client.hpp"
#include "fts/room/record.hpp"

using namespace fts;

namespace {

struct GameHostRig : test::HostRig {
  GameHostRig() {
    options.seed = 5;
    start();
  }
};

}  // namespace

TEST_CASE("Game host: clients join, ready up and the level starts", "[server][host]") {
  GameHostRig rig;
  auto& a = rig.add("ann");
  auto& b = rig.add("bob");
  for (int i = 0; i < 50 && (a.state() != protocol::ClientState::connected || b.state() != protocol::ClientState::connected); ++i)
    rig.tick();
  REQUIRE(a.state() == protocol::ClientState::connected);
  REQUIRE(b.state() == protocol::ClientState::connected);
  rig.tick();
  CHECK(rig.host->match().players.size() == 2);
  a.send_command(protocol::CommandOp::ready, 0, rig.now);
  b.send_command(protocol::CommandOp::ready, 0, rig.now);
  for (int i = 0; i < 20; ++i) rig.tick();
  CHECK(rig.host->match().phase == sim::Phase::playing);
  const auto results = a.take_results();
  REQUIRE(results.size() == 1);
  CHECK(results[0].ok);
  // Snapshots carry the level and both players.
  const auto snaps = a.take_snapshots();
  REQUIRE_FALSE(snaps.empty());
  CHECK(snaps.back().phase == protocol::Phase::play);
  CHECK(snaps.back().players.size() == 2);
}

TEST_CASE("Game host: a purchase in the wrong phase is refused with its reason", "[server][host]") {
  GameHostRig rig;
  auto& a = rig.add("ann");
  for (int i = 0; i < 50 && a.state() != protocol::ClientState::connected; ++i) rig.tick();
  REQUIRE(a.state() == protocol::ClientState::connected);
  a.send_command(protocol::CommandOp::buy, 'm', rig.now);
  for (int i = 0; i < 20; ++i) rig.tick();
  const auto results = a.take_results();
  REQUIRE(results.size() == 1);
  CHECK_FALSE(results[0].ok);
  CHECK(results[0].code == "phase");
  CHECK(rig.host->match().players[0].eco.coins == 0);
}

TEST_CASE("Game host: each command is answered with the step's result, by its rid", "[server][host]") {
  GameHostRig rig;
  auto& a = rig.add("ann");
  for (int i = 0; i < 50 && a.state() != protocol::ClientState::connected; ++i) rig.tick();
  REQUIRE(a.state() == protocol::ClientState::connected);
  rig.tick();
  const std::uint32_t again = a.send_command(protocol::CommandOp::play_again, 0, rig.now);
  const std::uint32_t ready = a.send_command(protocol::CommandOp::ready, 0, rig.now);
  for (int i = 0; i < 20; ++i) rig.tick();
  const auto results = a.take_results();
  REQUIRE(results.size() == 2);
  CHECK(results[0].command_rid == again);
  CHECK_FALSE(results[0].ok);
  CHECK(results[0].code == "phase");
  CHECK(results[1].command_rid == ready);
  CHECK(results[1].ok);
  CHECK(results[1].code == "ok");
  CHECK(rig.host->match().phase == sim::Phase::playing);
}

TEST_CASE("Game host: the record of a session replays with every hash equal", "[server][host]") {
  GameHostRig rig;
  test::RecordDir record("game-host");
  rig.host->record_to(record.path.string(), "test");
  auto& a = rig.add("ann");
  for (int i = 0; i < 50 && a.state() != protocol::ClientState::connected; ++i) rig.tick();
  a.send_command(protocol::CommandOp::ready, 0, rig.now);
  for (int i = 0; i < 400; ++i) {
    if (i % 3 == 0) a.send_input({0, static_cast<std::int8_t>(i % 2 ? 1 : -1), 1, false}, rig.now);
    rig.tick();
  }
  const auto live = sim::match_hash(rig.host->match());
  const auto ticks = rig.host->match().tick;
  rig.host.reset();  // the record's writer thread writes what is queued, then stops
  auto replay = room::replay_history(record.path);
  REQUIRE(std::holds_alternative<room::ReplayReport>(replay));
  const auto& rep = std::get<room::ReplayReport>(replay);
  CHECK(rep.format == "journal 1");
  CHECK(rep.hashes_checked == ticks / 10 + 1);  // a hash every 10 ticks, the first checkpoint's at 0
  CHECK(rep.final_hash == live);
}

TEST_CASE("Game host: --record holds room 1's record, --record-dir the other rooms'", "[server][host]") {
  test::HostRig rig;
  rig.options.seed = 5;
  rig.options.max_players = 2;  // four players: two rooms
  rig.start();
  test::RecordDir one("host-one"), rooms("host-rooms");
  std::filesystem::create_directories(rooms.path);
  rig.host->record_dir(rooms.path.string(), "test");
  rig.host->record_to(one.path.string(), "test");
  for (int i = 0; i < 4; ++i) rig.add("p" + std::to_string(i));
  REQUIRE(rig.connect_all());
  for (int i = 0; i < 100; ++i) rig.tick();
  REQUIRE(rig.host->room_ids() == std::vector<std::uint32_t>{1, 2});
  rig.host.reset();  // the records' writers write what is queued, then stop
  CHECK_FALSE(std::filesystem::exists(rooms.path / "room-1"));  // room 1 is --record's alone
  for (const auto& path : {one.path, rooms.path / "room-2"}) {
    INFO(path);
    auto replay = room::replay_history(path);  // each replays with every hash checked
    REQUIRE(std::holds_alternative<room::ReplayReport>(replay));
    CHECK(std::get<room::ReplayReport>(replay).hashes_checked > 1);
  }
}

TEST_CASE("Replay: a damaged record is refused with the line, not simulated for ever", "[server][replay]") {
  std::stringstream record;
  room::RecordWriter w(record, 1, sim::MatchConfig{}, "test");
  record << R"({"tick":1000000000000000,"hash":"0000000000000000"})" << "\n";
  auto r = room::replay_record(record);
  REQUIRE(std::holds_alternative<std::string>(r));
  CHECK(std::get<std::string>(r).rfind("line 2: tick 1000000000000000 is too far ahead", 0) == 0);
  std::stringstream bad;
  bad << "not json\n";
  CHECK(std::holds_alternative<std::string>(room::replay_record(bad)));
}

TEST_CASE("Game host: a chat line is relayed to every player with its sender, cleaned and rate-limited",
          "[server][host][chat]") {
  GameHostRig rig;
  auto& a = rig.add("ann");
  auto& b = rig.add("bob");
  for (int i = 0; i < 50 && (a.state() != protocol::ClientState::connected || b.state() != protocol::ClientState::connected); ++i)
    rig.tick();
  REQUIRE(b.state() == protocol::ClientState::connected);
  rig.tick();
  const std::uint32_t rid = a.send_chat("  hello \x1b[2J   bob ", rig.now);
  for (int i = 0; i < 20; ++i) rig.tick();
  const auto got = b.take_chats();
  REQUIRE(got.size() == 1);
  CHECK(got[0].from == a.welcome()->player_id);
  CHECK(got[0].name == "ann");
  CHECK(got[0].text == "hello ?[2J bob");  // no escape byte on the wire; spaces collapsed
  CHECK(a.take_chats().size() == 1);      // the sender sees its own line too
  const auto results = a.take_results();
  REQUIRE(results.size() == 1);
  CHECK(results[0].command_rid == rid);
  CHECK(results[0].ok);
  // A burst over the limit is refused with code "rate"; nothing more is relayed.
  for (int i = 0; i < 8; ++i) a.send_chat("spam", rig.now);
  for (int i = 0; i < 30; ++i) rig.tick();
  int refused = 0;
  for (const auto& r : a.take_results()) refused += (!r.ok && r.code == "rate") ? 1 : 0;
  CHECK(refused == 4);  // 5 lines per burst, one already said
  CHECK(b.take_chats().size() == 4);
}
