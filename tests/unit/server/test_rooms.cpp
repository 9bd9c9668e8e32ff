// Rooms (issue 13): real protocol clients against GameHost in memory, time stepped by
// hand: creation on demand, quick-play fill order, private codes, refusals, spectators,
// closing empty rooms, and the host's console.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "app/game_host.hpp"
#include "../../support/host_rig.hpp"
#include "app/room_codes.hpp"
#include "fts/protocol/client.hpp"

using namespace fts;
using protocol::ClientState;

namespace {

struct RoomsRig : test::HostRig {
  explicit RoomsRig(std::uint32_t seats = 2, std::uint32_t max_rooms = 4) {
    options.seed = 5;
    options.max_players = seats;
    options.max_rooms = max_rooms;
    options.max_spectators = 1;
    options.room_idle_ms = 1000;
    options.max_per_address = 64;
    start();
  }
  // A client that asks for `join` (and `room`); ticks until it is welcomed or refused.
  protocol::ClientEndpoint& add(const std::string& join = "", const std::string& room = "") {
    protocol::ClientConfig c;
    c.name = "p" + std::to_string(clients.size() + 1);
    c.join = join;
    c.room = room;
    auto& client = connect(c);
    for (int i = 0; i < 50 && client.state() == ClientState::connecting; ++i) tick();
    return client;
  }
  void ticks(int n) {
    for (int i = 0; i < n; ++i) tick();
  }
  static std::string room_of(const protocol::ClientEndpoint& c) { return c.welcome() ? c.welcome()->room : ""; }
};

}  // namespace

TEST_CASE("Rooms: quick play fills the fullest open room, then makes a new one", "[server][rooms]") {
  RoomsRig rig(2);
  auto& a = rig.add();
  auto& b = rig.add("quick");
  auto& c = rig.add("quick");
  REQUIRE(a.state() == ClientState::connected);
  REQUIRE(b.state() == ClientState::connected);
  REQUIRE(c.state() == ClientState::connected);
  CHECK(RoomsRig::room_of(a).size() == 5);
  CHECK(RoomsRig::room_of(b) == RoomsRig::room_of(a));  // a's room had a free seat
  CHECK(RoomsRig::room_of(c) != RoomsRig::room_of(a));  // full: a new room
  CHECK(rig.host->room_ids() == std::vector<std::uint32_t>{1, 2});
  // A private room with one player is never picked by quick play; the public room with
  // one player is (the fullest with a free seat).
  auto& d = rig.add("create");
  REQUIRE(d.state() == ClientState::connected);
  auto& e = rig.add("quick");
  REQUIRE(e.state() == ClientState::connected);
  CHECK(RoomsRig::room_of(e) == RoomsRig::room_of(c));
  rig.tick();
  // Each room's match holds its own players only.
  const auto* r1 = rig.host->room(1);
  const auto* r2 = rig.host->room(2);
  REQUIRE(r1);
  REQUIRE(r2);
  CHECK(r1->match().players.size() == 2);
  CHECK(r2->match().players.size() == 2);
  CHECK(sim::find_player(r1->match(), c.welcome()->player_id) == nullptr);
  CHECK(r1->seed() != r2->seed());
}

TEST_CASE("Rooms: join by code, and the refusals room_full, no_such_room, server_full", "[server][rooms]") {
  RoomsRig rig(2, 2);
  auto& owner = rig.add("create");
  REQUIRE(owner.state() == ClientState::connected);
  const std::string code = RoomsRig::room_of(owner);
  auto& friend_ = rig.add("join", code);
  REQUIRE(friend_.state() == ClientState::connected);
  CHECK(RoomsRig::room_of(friend_) == code);
  // Codes are typed by people: lower case is the same code.
  std::string lower = code;
  for (char& ch : lower) ch = static_cast<char>(ch - 'A' + 'a');
  auto& third = rig.add("join", lower);
  REQUIRE(third.state() == ClientState::refused);
  CHECK(third.error()->code == "room_full");
  auto& forged = rig.add("join", "QQQQQ");
  REQUIRE(forged.state() == ClientState::refused);
  CHECK(forged.error()->code == "no_such_room");
  auto& bad = rig.add("join", "I0L1O");
  REQUIRE(bad.state() == ClientState::refused);
  CHECK(bad.error()->code == "no_such_room");
  auto& weird = rig.add("dance");
  REQUIRE(weird.state() == ClientState::refused);
  CHECK(weird.error()->code == "bad_join");
  auto& second = rig.add("create");
  REQUIRE(second.state() == ClientState::connected);
  auto& over = rig.add("create");  // two rooms is the most
  REQUIRE(over.state() == ClientState::refused);
  CHECK(over.error()->code == "server_full");
  // Refusals changed nothing: two rooms, two and one players.
  CHECK(rig.host->room_ids().size() == 2);
  CHECK(rig.host->endpoint().seats_in_room(1) == 2);
  CHECK(rig.host->endpoint().seats_in_room(2) == 1);
  CHECK(rig.host->endpoint().rejects()[protocol::Reject::join_refused] == 3);  // room_full, bad_join, server_full
  CHECK(rig.host->endpoint().rejects()[protocol::Reject::unknown_room] == 2);
}

TEST_CASE("Rooms: a spectator has no ball and no seat, sees the room's snapshots, and is capped", "[server][rooms]") {
  RoomsRig rig(1);
  auto& player = rig.add("create");
  REQUIRE(player.state() == ClientState::connected);
  const std::string code = RoomsRig::room_of(player);
  auto& watcher = rig.add("spectate", code);
  REQUIRE(watcher.state() == ClientState::connected);
  CHECK(watcher.welcome()->spectator);
  CHECK(RoomsRig::room_of(watcher) == code);
  auto& second = rig.add("spectate", code);  // the cap is one
  REQUIRE(second.state() == ClientState::refused);
  CHECK(second.error()->code == "room_full");
  rig.ticks(3);
  const auto* room = rig.host->room(1);
  CHECK(room->match().players.size() == 1);  // no player for the spectator
  // The spectator's input and commands change nothing.
  watcher.send_input({0, 1, 0, true}, rig.now);
  const auto rid = watcher.send_command(protocol::CommandOp::ready, 0, rig.now);
  player.send_command(protocol::CommandOp::ready, 0, rig.now);
  std::vector<protocol::Result> results;
  for (int i = 0; i < 30; ++i) {
    rig.tick();
    for (auto& r : watcher.take_results()) results.push_back(r);
  }
  REQUIRE(results.size() == 1);
  CHECK(results[0].command_rid == rid);
  CHECK(results[0].code == "spectator");
  CHECK(room->match().players.size() == 1);
  // Both see the same snapshots of the room.
  const auto* ps = player.latest_snapshot();
  const auto* ws = watcher.latest_snapshot();
  REQUIRE(ps);
  REQUIRE(ws);
  CHECK(ps->tick == ws->tick);
  CHECK(ps->balls == ws->balls);
  CHECK(ps->players == ws->players);
}

TEST_CASE("Rooms: an empty room closes after room_idle_ms, and its code is gone", "[server][rooms]") {
  RoomsRig rig(2);
  auto& a = rig.add("create");
  REQUIRE(a.state() == ClientState::connected);
  const std::string code = RoomsRig::room_of(a);
  a.disconnect(rig.now);
  rig.ticks(50);  // 500 ms: still open
  CHECK(rig.host->room_ids().size() == 1);
  rig.ticks(60);  // past 1000 ms without anyone connected
  CHECK(rig.host->room_ids().empty());
  auto& late = rig.add("join", code);
  REQUIRE(late.state() == ClientState::refused);
  CHECK(late.error()->code == "no_such_room");
}

TEST_CASE("Rooms: the room list is a command's result, after the handshake", "[server][rooms]") {
  RoomsRig rig(2);
  auto& a = rig.add();
  auto& b = rig.add("create");  // private: not listed
  REQUIRE(a.state() == ClientState::connected);
  REQUIRE(b.state() == ClientState::connected);
  const auto rid = a.send_command(protocol::CommandOp::rooms, 0, rig.now);
  std::vector<protocol::Result> results;
  for (int i = 0; i < 20 && results.empty(); ++i) {
    rig.tick();
    results = a.take_results();
  }
  REQUIRE(results.size() == 1);
  CHECK(results[0].command_rid == rid);
  CHECK(results[0].ok);
  const std::string& list = results[0].message;
  CHECK(list.rfind(RoomsRig::room_of(a) + " 1/2 ", 0) == 0);
  CHECK(list.find("lobby") != std::string::npos);
  CHECK(list.find(RoomsRig::room_of(b)) == std::string::npos);
}

TEST_CASE("Room codes: five letters without look-alikes, redrawn on a collision", "[server][rooms]") {
  server::RoomCodes codes(42);
  std::set<std::string> taken;
  for (int i = 0; i < 200; ++i) {
    auto c = codes.next([&](const std::string& code) { return taken.count(code) > 0; });
    REQUIRE(c);
    CHECK(c->size() == 5);
    CHECK(c->find_first_of("ILO01") == std::string::npos);
    CHECK(taken.insert(*c).second);
  }
  // Every draw collides: a bounded number of draws, then no code.
  server::RoomCodes stuck(1);
  CHECK_FALSE(stuck.next([](const std::string&) { return true; }, 8));
  CHECK(stuck.draws() == 8);
  // The first draws collide: the next free one is returned.
  server::RoomCodes a(7), b(7);
  const auto first = *a.next([](const std::string&) { return false; });
  const auto second = *b.next([&](const std::string& c) { return c == first; });
  CHECK(second != first);
  CHECK(b.draws() == 2);
  CHECK(server::normalize_room_code("abcde") == "ABCDE");
  CHECK_FALSE(server::normalize_room_code("ABCDI"));
  CHECK_FALSE(server::normalize_room_code("ABCD"));
}

TEST_CASE("Console: rooms, players, kick (told why), close, drain and bad input", "[server][rooms][console]") {
  RoomsRig rig(2);
  auto& a = rig.add();
  auto& b = rig.add("create");
  REQUIRE(a.state() == ClientState::connected);
  REQUIRE(b.state() == ClientState::connected);
  rig.tick();
  auto rooms = rig.console(R"({"cmd":"rooms"})");
  REQUIRE(rooms["ok"] == true);
  REQUIRE(rooms["rooms"].size() == 2);
  CHECK(rooms["rooms"][0]["code"] == RoomsRig::room_of(a));
  CHECK(rooms["rooms"][1]["private"] == true);
  auto players = rig.console(R"({"cmd":"players","room":")" + RoomsRig::room_of(b) + R"("})");
  REQUIRE(players["players"].size() == 1);
  CHECK(players["players"][0]["player"] == b.welcome()->player_id);

  // Bad input: a clear error, nothing changed.
  CHECK(rig.console(R"({"cmd":"kick"})")["ok"] == false);
  CHECK(rig.console(R"({"cmd":"kick","player":99})")["ok"] == false);
  CHECK(rig.console(R"({"cmd":"kick","player":4294967297})")["ok"] == false);  // not player 1
  CHECK(rig.console(R"({"cmd":"players","room":4294967297})")["ok"] == false);
  CHECK(rig.console(R"({"cmd":"close","room":"ZZZZZ"})")["ok"] == false);
  CHECK(rig.console(R"({"cmd":"fly"})")["error"].get<std::string>().find("unknown command") != std::string::npos);
  CHECK(rig.console(R"([1,2])")["ok"] == false);
  CHECK(rig.host->room_ids().size() == 2);

  auto kicked = rig.console(R"({"cmd":"kick","player":)" + std::to_string(a.welcome()->player_id) +
                            R"(,"reason":"spamming"})");
  CHECK(kicked["ok"] == true);
  REQUIRE(a.error());
  CHECK(a.error()->code == "kicked");
  CHECK(a.error()->message == "kicked by the host: spamming");

  auto closed = rig.console(R"({"cmd":"close","room":")" + RoomsRig::room_of(b) + R"("})");
  CHECK(closed["ok"] == true);
  REQUIRE(b.error());
  CHECK(b.error()->code == "room_closed");

  auto stats = rig.console(R"({"cmd":"stats"})");
  CHECK(stats["rooms"] == 1);  // a's room, empty, not closed yet

  CHECK(rig.console(R"({"cmd":"drain"})")["ok"] == true);
  CHECK_FALSE(rig.host->drained());
  auto& late = rig.add("create");  // no new rooms while draining
  REQUIRE(late.state() == ClientState::refused);
  CHECK(late.error()->code == "server_full");
  rig.ticks(120);  // the last room empties out
  CHECK(rig.host->drained());
}

TEST_CASE("Console: a ban drops the address's sessions and datagrams", "[server][rooms][console]") {
  RoomsRig rig(2);
  auto& a = rig.add();
  REQUIRE(a.state() == ClientState::connected);
  auto banned = rig.console(R"({"cmd":"ban","address":"10.0.0.1","minutes":1})");
  CHECK(banned["ok"] == true);
  REQUIRE(a.error());
  CHECK(a.error()->code == "banned");
  CHECK(rig.console(R"({"cmd":"ban","address":"10.0.0.1","minutes":0})")["ok"] == false);
  // The same address again: nothing answers.
  a.connect(rig.now);
  rig.ticks(20);
  CHECK(a.state() == ClientState::connecting);
  CHECK(rig.console(R"({"cmd":"stats"})")["banned_datagrams"].get<std::uint64_t>() > 0);
}

TEST_CASE("Rooms: a token takes the player back into its own room", "[server][rooms]") {
  RoomsRig rig(2);
  auto& a = rig.add();           // room 1
  auto& b = rig.add("create");   // room 2, private
  REQUIRE(b.state() == ClientState::connected);
  const std::string code = RoomsRig::room_of(b);
  const auto id = b.welcome()->player_id;
  rig.ticks(3);
  // b's process restarts: a new client from a new port with the token, asking for
  // quick play, which the token overrides.
  protocol::ClientConfig c;
  c.name = "p2";
  c.token = b.welcome()->token;
  c.join = "quick";
  rig.clients[1] = std::make_unique<protocol::ClientEndpoint>(c);
  auto& back = *rig.clients[1];
  back.connect(rig.now);
  for (int i = 0; i < 50 && back.state() == ClientState::connecting; ++i) rig.tick();
  REQUIRE(back.state() == ClientState::connected);
  CHECK(back.welcome()->reconnected);
  CHECK(back.welcome()->player_id == id);
  CHECK(RoomsRig::room_of(back) == code);
  rig.ticks(3);
  CHECK(sim::find_player(rig.host->room(2)->match(), id) != nullptr);
  CHECK(sim::find_player(rig.host->room(1)->match(), id) == nullptr);
  CHECK(a.state() == ClientState::connected);
}

TEST_CASE("Rooms: a host guessing room codes is refused after 10 misses, then gets 6 a minute", "[server][rooms]") {
  RoomsRig rig(8);
  auto& owner = rig.add("create");
  REQUIRE(owner.state() == ClientState::connected);
  const std::string code = RoomsRig::room_of(owner);
  const auto& rejects = rig.host->endpoint().rejects();
  // Every guess is a new hello from the same host (its own port): 10 wrong codes are
  // answered no_such_room, then even the right code is refused before it is looked at.
  rig.next_host = "10.9.9.9";
  const std::string wrong = code == "QQQQQ" ? "ZZZZZ" : "QQQQQ";
  for (int i = 0; i < 10; ++i) {
    auto& guess = rig.add(i % 2 ? "join" : "spectate", wrong);
    REQUIRE(guess.state() == ClientState::refused);
    CHECK(guess.error()->code == "no_such_room");
  }
  CHECK(rejects[protocol::Reject::unknown_room] == 10);
  auto& right = rig.add("join", code);
  REQUIRE(right.state() == ClientState::refused);
  CHECK(right.error()->code == "rate_limited");
  auto& watch = rig.add("spectate", code);
  REQUIRE(watch.state() == ClientState::refused);
  CHECK(rejects[protocol::Reject::code_limited] == 2);
  CHECK(rejects[protocol::Reject::unknown_room] == 10);  // the code was not looked at
  // Quick play and create ask for no code: the host still plays.
  auto& quick = rig.add("quick");
  CHECK(quick.state() == ClientState::connected);
  // Another host joins by the code as before.
  rig.next_host = "10.8.8.8";
  auto& friend_ = rig.add("join", code);
  REQUIRE(friend_.state() == ClientState::connected);
  CHECK(RoomsRig::room_of(friend_) == code);
  // 10 s later the guesser has one more miss (6 a minute): the right code gets in, and
  // a right code costs nothing.
  rig.next_host = "10.9.9.9";
  for (int t = 0; t < 1000; ++t) rig.tick();
  auto& back = rig.add("join", code);
  REQUIRE(back.state() == ClientState::connected);
  auto& miss = rig.add("join", wrong);
  REQUIRE(miss.state() == ClientState::refused);
  CHECK(miss.error()->code == "no_such_room");
  auto& over = rig.add("join", code);
  REQUIRE(over.state() == ClientState::refused);
  CHECK(over.error()->code == "rate_limited");
  CHECK(rejects[protocol::Reject::code_limited] == 3);
}

TEST_CASE("Rooms: a spectator flood fills the room's spectator cap and no more - the players play on", "[server][rooms]") {
  test::HostRig rig;
  rig.options.seed = 5;
  rig.options.max_players = 2;
  rig.options.max_spectators = 8;
  rig.options.max_per_address = 64;
  rig.start();
  protocol::ClientConfig a, b;
  a.name = "ann";
  a.join = "create";
  auto& ann = rig.connect(a);
  REQUIRE(rig.connect_all());
  b.name = "bob";
  b.join = "join";
  b.room = RoomsRig::room_of(ann);
  auto& bob = rig.connect(b);
  REQUIRE(rig.connect_all());
  // 400 spectators from 400 hosts and 40 from one host ask at once.
  std::vector<protocol::ClientEndpoint*> flood;
  for (int i = 0; i < 440; ++i) {
    rig.next_host = i < 400 ? "10.7." + std::to_string(i / 200) + "." + std::to_string(i % 200 + 1) : "10.6.6.6";
    protocol::ClientConfig c;
    c.name = "w" + std::to_string(i);
    c.join = "spectate";
    c.room = b.room;
    flood.push_back(&rig.connect(c));
  }
  const auto snapshot_tick = [](const protocol::ClientEndpoint& c) {
    return c.latest_snapshot() ? c.latest_snapshot()->tick : 0;
  };
  std::uint64_t last = snapshot_tick(ann);
  int waiting = 440;
  for (int t = 0; t < 600 && waiting > 0; ++t) {
    rig.tick();
    if (t % 20 == 19) {  // the players' snapshots keep coming through the flood
      CHECK(snapshot_tick(ann) > last);
      CHECK(snapshot_tick(bob) == snapshot_tick(ann));
      last = snapshot_tick(ann);
    }
    waiting = static_cast<int>(std::count_if(flood.begin(), flood.end(), [](const auto* c) {
      return c->state() == ClientState::connecting;
    }));
  }
  REQUIRE(waiting == 0);
  const auto watching = std::count_if(flood.begin(), flood.end(), [](const auto* c) {
    return c->state() == ClientState::connected;
  });
  CHECK(watching == 8);
  for (const auto* c : flood)
    if (c->state() != ClientState::connected) CHECK(c->error()->code == "room_full");
  CHECK(rig.host->endpoint().spectators_in_room(1) == 8);
  CHECK(rig.host->room_ids().size() == 1);
  CHECK(rig.host->room(1)->match().players.size() == 2);
  CHECK(ann.state() == ClientState::connected);
  CHECK(bob.state() == ClientState::connected);
}
