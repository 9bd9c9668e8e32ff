// GameHost with a journal per room (issue 15), real protocol clients in memory, time
// stepped by hand: a host that dies is rebuilt from its rooms' journals by another host
// (a new key); each client that comes back with its token finds its player as it was, in
// its room, under its code. A room that closes takes its journal with it.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "../../support/host_rig.hpp"
#include "app/game_host.hpp"
#include "app/room_journals.hpp"

using namespace fts;
namespace fs = std::filesystem;
using protocol::ClientState;

namespace {

struct Rig : test::HostRig {
  store::JournalConfig jc;
  Rig(const fs::path& root, std::uint8_t key_byte) {
    options.seed = 11;
    options.max_players = 2;
    options.max_per_address = 64;
    options.room_idle_ms = 1000;
    jc.dir = root;
    jc.sync_ms = 5;
    jc.checkpoint_every_ticks = 150;
    key.fill(key_byte);
    start();
    host->journal_rooms(jc);
  }
  const server::Room& room_of(const protocol::ClientEndpoint& c) const {
    return *host->room_by_code(c.welcome()->room);
  }
};

// Waits (with a deadline) until the closed rooms' writers have removed their journals.
bool journals_finished(Rig& rig) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (rig.host->closing_journals() > 0 && std::chrono::steady_clock::now() < deadline) {
    rig.tick();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return rig.host->closing_journals() == 0;
}

}  // namespace

TEST_CASE("Host resume: every room comes back under its code, each player by token into its room", "[journal][host]") {
  const fs::path root = fs::temp_directory_path() / ("fts-host-resume-" + std::to_string(::getpid()));
  fs::remove_all(root);
  struct Seat {
    std::string name, token, code;
    std::uint32_t id = 0;
  };
  std::vector<Seat> seats;
  std::map<std::string, sim::MatchState> crashed;  // by room code
  std::map<std::string, std::uint32_t> room_ids;
  {
    Rig a(root, 1);
    auto& ann = a.join("ann", "create");
    auto& bob = a.join("bob", "create");
    REQUIRE(ann.state() == ClientState::connected);
    REQUIRE(bob.state() == ClientState::connected);
    auto& cat = a.join("cat", "join", ann.welcome()->room);
    REQUIRE(cat.state() == ClientState::connected);
    REQUIRE(ann.welcome()->room != bob.welcome()->room);
    for (auto* c : {&ann, &bob, &cat}) c->send_command(protocol::CommandOp::ready, 0, a.now);
    for (int i = 0; i < 400; ++i) {
      for (auto* c : {&ann, &bob, &cat})
        c->send_input({0, static_cast<std::int8_t>(i % 60 < 30 ? 1 : -1), 0, i % 20 == 0}, a.now);
      a.tick();
    }
    for (const auto& [name, c] : {std::pair{"ann", &ann}, std::pair{"bob", &bob}, std::pair{"cat", &cat}})
      seats.push_back({name, c->welcome()->token, c->welcome()->room, c->welcome()->player_id});
    for (auto id : a.host->room_ids()) {
      const server::Room& r = *a.host->room(id);
      REQUIRE(r.match().phase == sim::Phase::playing);
      a.host->journal(id)->flush();
      crashed[r.code()] = r.match();
      room_ids[r.code()] = id;
    }
  }  // the process is gone (its journals were synced up to here)

  server::JournalRoot dir(root);
  REQUIRE(dir.error().empty());
  const auto codes = dir.room_codes();
  REQUIRE(codes.size() == 2);
  const auto reads = server::read_room_journals(root, codes, 2);
  Rig b(root, 2);
  b.now = 50;
  const auto sum = server::resume_rooms(*b.host, reads, *server::resumed_config(reads), b.now);
  CHECK(sum.resumed == 2);
  CHECK(sum.skipped == 0);
  CHECK(sum.sessions == 3);
  for (const auto& [code, state] : crashed) {
    const server::Room* r = b.host->room_by_code(code);
    REQUIRE(r);
    CHECK(r->id() == room_ids.at(code));
    CHECK(r->is_private());
    CHECK(r->match().tick == state.tick);
    CHECK(sim::match_hash(r->match()) == sim::match_hash(state));
  }
  b.tick();
  for (const auto& s : seats) {
    const sim::Player* p = sim::find_player(b.host->room_by_code(s.code)->match(), s.id);
    REQUIRE(p);
    CHECK_FALSE(p->connected);  // away until its client comes back
  }
  // A new room made now gets a new id and code, and journals too.
  auto& dan = b.join("dan", "create");
  REQUIRE(dan.state() == ClientState::connected);
  CHECK(b.room_of(dan).id() == 3);
  CHECK(b.host->journal(3));
  for (const auto& s : seats) {
    auto& c = b.join(s.name, "", "", s.token);
    REQUIRE(c.state() == ClientState::connected);
    CHECK(c.welcome()->reconnected);
    CHECK(c.welcome()->player_id == s.id);
    CHECK(c.welcome()->room == s.code);
  }
  b.tick();
  for (const auto& s : seats) {
    const sim::Player* p = sim::find_player(b.host->room_by_code(s.code)->match(), s.id);
    REQUIRE(p);
    CHECK(p->connected);
    const sim::Player* before = sim::find_player(crashed.at(s.code), s.id);
    CHECK(p->eco.coins == before->eco.coins);
    CHECK(p->eco.lives == before->eco.lives);
    CHECK(p->eco.mass == before->eco.mass);
    CHECK(b.host->room_by_code(s.code)->match().level == crashed.at(s.code).level);
  }

  // A room that closes takes its journal with it: a later resume does not bring it back.
  const std::string closed = seats[1].code;
  CHECK(b.console(R"({"cmd":"close","room":")" + closed + R"("})")["ok"] == true);
  REQUIRE(journals_finished(b));
  CHECK_FALSE(fs::exists(root / closed));
  CHECK_FALSE(fs::exists(root / (closed + ".closed")));
  CHECK(fs::exists(root / seats[0].code));
  b.host.reset();
  fs::remove_all(root);
}

TEST_CASE("Journal root: one server at a time - only room codes are rooms - finished leftovers go", "[journal][host]") {
  const fs::path root = fs::temp_directory_path() / ("fts-journal-root-" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "ABCDE");
  fs::create_directories(root / "main");
  fs::create_directories(root / "BCDEF.closed");
  fs::create_directories(root / "CDEFG");  // handed over to a peer before the server stopped
  std::ofstream(root / "CDEFG" / server::JournalRoot::kMovedMark).put('\n');
  {
    server::JournalRoot first(root);
    REQUIRE(first.error().empty());
    CHECK(first.room_codes() == std::vector<std::string>{"ABCDE"});
    CHECK_FALSE(fs::exists(root / "BCDEF.closed"));
    CHECK_FALSE(fs::exists(root / "CDEFG"));
    server::JournalRoot second(root);
    CHECK_THAT(second.error(), Catch::Contains("in use by another server"));
  }
  server::JournalRoot again(root);  // the lock went with the first
  CHECK(again.error().empty());
  fs::remove_all(root);
}

TEST_CASE("Host resume: a room with nothing usable or another config is skipped, the others resume", "[journal][host]") {
  const fs::path root = fs::temp_directory_path() / ("fts-journal-skip-" + std::to_string(::getpid()));
  fs::remove_all(root);
  sim::MatchConfig cfg, other;
  other.player_lives = cfg.player_lives + 3;
  auto write = [&](const std::string& code, std::uint32_t id, const sim::MatchConfig& c) {
    store::JournalConfig jc;
    jc.dir = root / code;
    jc.room = code;
    jc.room_id = id;
    jc.seed = 100 + id;
    sim::MatchState s = sim::make_match(c, jc.seed);
    store::JournalWriter w(jc, c, s, 0, {{1, "ann", std::string(32, 'a'), false}});
    for (int i = 0; i < 30; ++i) {
      w.inputs(s.tick, {});
      sim::step(s, {});
      w.stepped(s, 0);
    }
    return s;
  };
  const auto good = write("BCDEF", 4, cfg);
  write("CDEFG", 5, other);
  fs::create_directories(root / "DEFGH");
  std::ofstream(root / "DEFGH" / store::segment_name(1)) << "{\"fts_journal\":1\n";
  const std::vector<std::string> codes{"BCDEF", "CDEFG", "DEFGH"};
  const auto reads = server::read_room_journals(root, codes, 3);
  REQUIRE(reads.size() == 3);
  CHECK(std::holds_alternative<std::string>(reads[2].result));
  Rig b(root, 3);
  const auto sum = server::resume_rooms(*b.host, reads, cfg, b.now);
  CHECK(sum.rooms == 3);
  CHECK(sum.resumed == 1);
  CHECK(sum.skipped == 2);
  const server::Room* r = b.host->room_by_code("BCDEF");
  REQUIRE(r);
  CHECK(r->id() == 4);
  CHECK(r->seed() == 104);
  CHECK_FALSE(r->is_private());
  CHECK(sim::match_hash(r->match()) == sim::match_hash(good));
  CHECK_FALSE(b.host->room_by_code("CDEFG"));
  CHECK(fs::exists(root / "CDEFG"));  // left on disk, reported
  b.host.reset();
  fs::remove_all(root);
}

// Issue 36 point 10: a resumed room's players keep their ids, and a newcomer after the
// resume gets an id above every id the room names (a new session took the lowest free
// one, 1 here, below the resumed player's).
TEST_CASE("Host resume: a newcomer's id is above every resumed player's", "[journal][host][ids]") {
  const fs::path root = fs::temp_directory_path() / ("fts-host-resume-ids-" + std::to_string(::getpid()));
  fs::remove_all(root);
  std::uint32_t bob_id = 0;
  std::string code;
  {
    Rig a(root, 1);
    auto& ann = a.join("ann", "create");
    REQUIRE(ann.state() == ClientState::connected);
    code = ann.welcome()->room;
    auto& bob = a.join("bob", "join", code);
    REQUIRE(bob.state() == ClientState::connected);
    bob_id = bob.welcome()->player_id;
    bob.send_command(protocol::CommandOp::ready, 0, a.now);
    REQUIRE(a.console(R"({"cmd":"kick","player":)" + std::to_string(ann.welcome()->player_id) + "}")["ok"] == true);
    for (int i = 0; i < 100; ++i) {
      bob.send_input({0, 1, 0, false}, a.now);
      a.tick();
    }
    REQUIRE(a.host->room_by_code(code));
    a.host->journal(a.host->room_by_code(code)->id())->flush();
  }
  const auto reads = server::read_room_journals(root, {code}, 2);
  Rig b(root, 2);
  b.now = 50;
  REQUIRE(server::resume_rooms(*b.host, reads, *server::resumed_config(reads), b.now).sessions == 1);
  b.tick();
  REQUIRE(sim::find_player(b.host->room_by_code(code)->match(), bob_id));
  auto& cy = b.join("cy", "join", code);
  REQUIRE(cy.state() == ClientState::connected);
  CHECK(cy.welcome()->player_id > bob_id);
  b.host.reset();
  fs::remove_all(root);
}
