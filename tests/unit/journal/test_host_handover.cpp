// Rooms that move (issue 42), the hosts' side without sockets: a room exported from one
// GameHost (frozen, its journal synced) is adopted by another at the same tick and hash;
// the first tells the room's clients (moved) and closes it; each refusal of adopt_room
// changes nothing, and a room kept plays on.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <chrono>
#include <filesystem>

#include "../../support/host_rig.hpp"
#include "app/game_host.hpp"
#include "app/room_journals.hpp"

using namespace fts;
namespace fs = std::filesystem;
using protocol::ClientState;

namespace {

struct HandoverRig : test::HostRig {
  HandoverRig(const fs::path& root, std::uint8_t key_byte, std::uint32_t max_players = 2) {
    options.seed = 11;
    options.max_players = max_players;
    options.max_per_address = 64;
    store::JournalConfig jc;
    jc.dir = root;
    jc.sync_ms = 5;
    key.fill(key_byte);
    start();
    host->journal_rooms(jc);
  }
};

fs::path fresh_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("fts-handover-" + name + "-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::remove_all(p, ec);
  return p;
}

}  // namespace

TEST_CASE("Host hand-over: the peer runs the room at its tick and hash, and its clients are told", "[journal][handover]") {
  const fs::path ra = fresh_dir("a"), rb = fresh_dir("b"), rc = fresh_dir("c");
  HandoverRig a(ra, 1), b(rb, 2), c(rc, 3);
  auto& ann = a.join("ann", "create");
  REQUIRE(ann.state() == ClientState::connected);
  const std::string code = ann.welcome()->room;
  ann.send_command(protocol::CommandOp::ready, 0, a.now);
  for (int i = 0; i < 200; ++i) {
    ann.send_input({0, 1, 0, i % 20 == 0}, a.now);
    a.tick();
  }
  REQUIRE(a.host->room_by_code(code)->match().phase == sim::Phase::playing);

  // Refusals before anything moves: no such room; a peer of another match configuration.
  CHECK(std::get<std::string>(a.host->export_rooms({"QQQQQ"})[0]) == "no room QQQQQ on this server");
  auto exported = a.host->export_rooms({code})[0];
  REQUIRE(std::holds_alternative<server::GameHost::RoomExport>(exported));
  const auto ex = std::get<server::GameHost::RoomExport>(exported);
  CHECK(std::get<std::string>(a.host->export_rooms({code})[0]).find("being handed over already") != std::string::npos);
  // Frozen: the room does not step while the peer decides.
  for (int i = 0; i < 10; ++i) a.tick();
  CHECK(a.host->room_by_code(code)->match().tick == ex.tick);

  // The peer refuses what it cannot take, and nothing changes there.
  auto renamed = ex.files;
  renamed[0].first = "../../etc/passwd";
  CHECK(b.host->adopt_room(code, renamed, b.now) == "a file that is not a journal segment came");
  auto torn = ex.files;
  torn[0].second = "{\"fts_journal\":1\n";
  CHECK(b.host->adopt_room(code, torn, b.now).find("its journal does not read") == 0);
  CHECK(b.host->adopt_room("nope", ex.files, b.now) == "not a room code");
  auto& cat = c.join("cat", "create");  // c's own player 1: the room's ann is player 1 too
  REQUIRE(cat.state() == ClientState::connected);
  CHECK(c.host->adopt_room(code, ex.files, c.now) == "player id 1 is in use here");
  CHECK(c.host->room_by_code(code) == nullptr);
  CHECK_FALSE(fs::exists(rc / code));
  CHECK(b.host->room_ids().empty());

  // The peer takes it: the same tick, the same state.
  REQUIRE(b.host->adopt_room(code, ex.files, b.now) == "");
  const server::Room* there = b.host->room_by_code(code);
  REQUIRE(there);
  CHECK(there->match().tick == ex.tick);
  CHECK(sim::match_hash(there->match()) == sim::match_hash(a.host->room_by_code(code)->match()));
  CHECK(b.host->rooms_adopted() == 1);
  // A second copy is refused there: the room is open (handed over twice).
  CHECK(b.host->adopt_room(code, ex.files, b.now).find("is open here already") != std::string::npos);

  // Then the first server tells the room's clients and closes it without a result.
  CHECK(a.host->room_moved(code, "10.0.0.9:7778", a.now) == 1);
  CHECK(a.host->room_by_code(code) == nullptr);
  CHECK(a.host->rooms_moved() == 1);
  for (int i = 0; i < 5 && !ann.moved(); ++i) a.tick();
  REQUIRE(ann.moved());
  CHECK(ann.moved()->address == "10.0.0.9:7778");
  CHECK(ann.moved()->room == code);
  std::error_code ec;  // (a closed room's writer may be removing its directory now)
  for (auto* r : {&ra, &rb, &rc}) fs::remove_all(*r, ec);
}

TEST_CASE("Host hand-over: a room the peer refused plays on where it was", "[journal][handover]") {
  const fs::path ra = fresh_dir("kept");
  HandoverRig a(ra, 1);
  auto& ann = a.join("ann", "create");
  REQUIRE(ann.state() == ClientState::connected);
  const std::string code = ann.welcome()->room;
  ann.send_command(protocol::CommandOp::ready, 0, a.now);
  for (int i = 0; i < 50; ++i) a.tick();
  REQUIRE(std::holds_alternative<server::GameHost::RoomExport>(a.host->export_rooms({code})[0]));
  const auto frozen_at = a.host->room_by_code(code)->match().tick;
  a.host->room_kept(code, "the peer is full");
  CHECK(a.host->handovers_refused() == 1);
  for (int i = 0; i < 20; ++i) a.tick();
  CHECK(a.host->room_by_code(code)->match().tick > frozen_at);
  CHECK_FALSE(ann.moved());
  CHECK(ann.state() == ClientState::connected);
  // A draining server takes no room.
  a.host->stop_new_rooms();
  CHECK(a.host->adopt_room("BBBBB", {{"journal-000001.jsonl", "{}\n"}}, a.now) == "this server is draining");
  std::error_code ec;
  fs::remove_all(ra, ec);
}

TEST_CASE("Host hand-over: rooms exported together are each frozen or refused on their own", "[journal][handover]") {
  const fs::path ra = fresh_dir("together");
  HandoverRig a(ra, 1);
  auto& ann = a.join("ann", "create");
  auto& bob = a.join("bob", "create");
  REQUIRE(ann.state() == ClientState::connected);
  REQUIRE(bob.state() == ClientState::connected);
  const std::string one = ann.welcome()->room, two = bob.welcome()->room;
  REQUIRE(one != two);
  for (auto* c : {&ann, &bob}) c->send_command(protocol::CommandOp::ready, 0, a.now);
  for (int i = 0; i < 50; ++i) a.tick();
  const auto tick_one = a.host->room_by_code(one)->match().tick;
  const auto tick_two = a.host->room_by_code(two)->match().tick;

  auto out = a.host->export_rooms({one, "QQQQQ", two, one});
  REQUIRE(out.size() == 4);
  REQUIRE(std::holds_alternative<server::GameHost::RoomExport>(out[0]));
  CHECK(std::get<std::string>(out[1]) == "no room QQQQQ on this server");
  REQUIRE(std::holds_alternative<server::GameHost::RoomExport>(out[2]));
  CHECK(std::get<std::string>(out[3]).find("named twice") != std::string::npos);
  const auto& ex_one = std::get<server::GameHost::RoomExport>(out[0]);
  const auto& ex_two = std::get<server::GameHost::RoomExport>(out[2]);
  CHECK(ex_one.code == one);
  CHECK(ex_two.code == two);
  CHECK(ex_one.tick == tick_one);
  CHECK(ex_two.tick == tick_two);
  // Each ships the segment its own checkpoint began, synced to the tick it stopped at.
  for (const auto* ex : {&ex_one, &ex_two}) {
    REQUIRE(ex->files.size() == 1);
    CHECK(ex->files[0].second.find("\"room\":\"" + ex->code + "\"") != std::string::npos);
  }
  // Both frozen; one kept plays on while the other stays frozen.
  a.host->room_kept(one, "the peer is full");
  for (int i = 0; i < 10; ++i) a.tick();
  CHECK(a.host->room_by_code(one)->match().tick > tick_one);
  CHECK(a.host->room_by_code(two)->match().tick == tick_two);
  std::error_code ec;
  fs::remove_all(ra, ec);
}

namespace {

// Ticks `rig` until its closed rooms' journal writers have stopped (real threads), for at
// most two seconds of wall time.
void until_journals_closed(HandoverRig& rig) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (rig.host->closing_journals() != 0 && std::chrono::steady_clock::now() < until) rig.tick();
}

}  // namespace

TEST_CASE("Host hand-over: an adopted room is held until confirmed, else forgotten", "[journal][handover]") {
  const fs::path ra = fresh_dir("held-a"), rb = fresh_dir("held-b");
  HandoverRig a(ra, 1, 4), b(rb, 2, 4);
  std::vector<std::string> codes;
  std::vector<protocol::ClientEndpoint*> players;
  for (const char* name : {"ann", "bob", "cid"}) {
    auto& c = a.join(name, "create");
    REQUIRE(c.state() == ClientState::connected);
    codes.push_back(c.welcome()->room);
    players.push_back(&c);
    c.send_command(protocol::CommandOp::ready, 0, a.now);
  }
  for (int i = 0; i < 50; ++i) a.tick();
  const auto out = a.host->export_rooms(codes);
  for (std::size_t i = 0; i < codes.size(); ++i) {
    REQUIRE(std::holds_alternative<server::GameHost::RoomExport>(out[i]));
    REQUIRE(b.host->adopt_room(codes[i], std::get<server::GameHost::RoomExport>(out[i]).files, b.now) == "");
    CHECK(b.host->unconfirmed(codes[i]));
    CHECK(fs::exists(rb / codes[i] / server::JournalRoot::kUnconfirmedMark));
  }
  const std::string& by_sender = codes[0];  // the confirmation came
  const std::string& by_client = codes[1];  // its player came back to the peer
  const std::string& lost = codes[2];       // neither: the sender kept it
  // Held: nobody new is put in it, by quick play or by its code.
  auto& dan = b.join("dan", "join", lost);
  CHECK(dan.state() != ClientState::connected);
  CHECK(b.host->room_by_code(lost)->match().players.size() == 1);
  // Nor is it handed on: the copy may be the sender's to keep.
  CHECK(std::get<std::string>(b.host->export_rooms({lost})[0]).find("still arriving here") != std::string::npos);

  CHECK(b.host->confirm_adopted(by_sender, "sender"));
  CHECK_FALSE(b.host->confirm_adopted(by_sender, "sender"));  // once
  CHECK_FALSE(b.host->unconfirmed(by_sender));
  CHECK_FALSE(fs::exists(rb / by_sender / server::JournalRoot::kUnconfirmedMark));
  // The sender tells bob's room, and bob comes back to the peer with his token.
  CHECK(a.host->room_moved(by_client, "10.0.0.9:7778", a.now) == 1);
  auto& bob_there = b.join("bob", "", "", players[1]->welcome()->token);
  REQUIRE(bob_there.state() == ClientState::connected);
  CHECK(bob_there.welcome()->room == by_client);
  CHECK_FALSE(b.host->unconfirmed(by_client));
  CHECK(b.host->unconfirmed(lost));

  // 10 s on: the room nobody confirmed is forgotten, with its journal; the others play on.
  const auto at = b.host->room_by_code(lost)->match().tick;
  for (std::uint64_t t = 0; t <= server::GameHost::kUnconfirmedMs / 10; ++t) b.tick();
  CHECK(b.host->room_by_code(lost) == nullptr);
  CHECK(b.host->rooms_forgotten() == 1);
  CHECK(b.host->room_by_code(by_sender) != nullptr);
  CHECK(b.host->room_by_code(by_client) != nullptr);
  until_journals_closed(b);
  CHECK_FALSE(fs::exists(rb / lost));
  CHECK(fs::exists(rb / by_sender));
  // The sender's copy of it plays on once kept.
  a.host->room_kept(lost, "the peer's answer was lost");
  for (int i = 0; i < 20; ++i) a.tick();
  CHECK(a.host->room_by_code(lost)->match().tick > at);
  std::error_code ec;
  for (auto* r : {&ra, &rb}) fs::remove_all(*r, ec);
}
