// What a pool's job is handed (issue 39, server_jobs.hpp): an InboxJob screens, opens and
// applies the queued datagrams of one shard of the sessions, each with its session's seal,
// whatever order the jobs run in; a datagram from another address, or of a session gone
// since it came, is counted and applies nothing; RoomSessions
// hands a room's snapshot job its connected sessions and nothing else, made again when
// one comes or goes; a room's TimerJob keeps its own sessions alive, and what the timer
// jobs find is settled in room order whatever order they ran in.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <set>

#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

// Players taken into rooms 1 and 2 in turn (1, 2, 1, ...).
struct TwoRooms {
  ServerConfig config = test_server_config();
  std::unique_ptr<ServerEndpoint> server;
  std::vector<std::unique_ptr<ClientEndpoint>> clients;
  std::vector<Address> addresses;
  std::uint64_t now = 100;
  std::uint32_t admitted = 0;

  TwoRooms() {
    config.admit = [this](const JoinAsk&) {
      Admission a;
      a.room = 1 + (admitted++ % 2);
      return a;
    };
    server = std::make_unique<ServerEndpoint>(config);
  }
  ClientEndpoint& add(const std::string& name) {
    ClientConfig c;
    c.name = name;
    clients.push_back(std::make_unique<ClientEndpoint>(c));
    addresses.push_back("10.0.0." + std::to_string(clients.size()) + ":5000");
    clients.back()->connect(now);
    return *clients.back();
  }
  // Steps until every client is connected (false: not within 200 steps).
  bool connect_all() {
    const auto connected = [](const auto& c) { return c->state() == ClientState::connected; };
    for (int i = 0; i < 200 && !std::all_of(clients.begin(), clients.end(), connected); ++i) step(false);
    return std::all_of(clients.begin(), clients.end(), connected);
  }
  // Client datagrams to the server: at once (handshake), or queued for the inbox.
  void step(bool queue) {
    now += 5;
    for (std::size_t i = 0; i < clients.size(); ++i) {
      clients[i]->update(now);
      for (auto& d : clients[i]->take_datagrams()) {
        if (queue) server->receive_later(addresses[i], d, now);
        else server->receive(addresses[i], d, now);
      }
    }
    for (auto& out : server->take_datagrams())
      for (std::size_t i = 0; i < clients.size(); ++i)
        if (addresses[i] == out.to) clients[i]->receive(out.bytes, now);
    server->update(now);
  }
};

}  // namespace

TEST_CASE("Server jobs: each inbox job screens and opens its own shard's datagrams, in any order",
          "[protocol][threads]") {
  TwoRooms t;
  for (int i = 0; i < 12; ++i) t.add("p" + std::to_string(i));
  REQUIRE(t.connect_all());
  t.server->take_events();
  t.server->take_inputs();
  std::map<std::uint32_t, unsigned> shard_of_player;  // from the datagrams' own headers
  const auto queue_inputs = [&] {
    t.now += 1;
    for (std::size_t c = 0; c < t.clients.size(); ++c) {
      t.clients[c]->send_input({1, 0, 0, false}, t.now);
      t.clients[c]->update(t.now);
      for (auto& d : t.clients[c]->take_datagrams()) {
        const auto h = read_header_any_version(d);
        REQUIRE(h);
        shard_of_player[t.clients[c]->welcome()->player_id] = SessionShard::of(h->session);
        t.server->receive_later(t.addresses[c], d, t.now);
      }
    }
  };

  // Three inputs each, queued; the jobs run last first; every input comes out once, in order.
  for (int i = 0; i < 3; ++i) queue_inputs();
  CHECK(t.server->inbox_datagrams() >= 36);
  const auto jobs = t.server->inbox_jobs();
  std::set<unsigned> shards;
  for (const InboxJob* job : jobs) shards.insert(job->shard());
  std::set<unsigned> expected_shards;
  for (const auto& [player, shard] : shard_of_player) expected_shards.insert(shard);
  CHECK(shards == expected_shards);  // one job per shard with datagrams, each once
  REQUIRE(jobs.size() >= 2);  // twelve random session ids in 64 shards
  std::vector<std::uint8_t> scratch;
  for (auto it = jobs.rbegin(); it != jobs.rend(); ++it) (*it)->run(scratch);
  t.server->apply_inbox();
  std::map<std::uint32_t, std::vector<std::uint32_t>> seqs;
  for (const auto& in : t.server->take_inputs()) seqs[in.player_id].push_back(in.frame.seq);
  CHECK(seqs.size() == t.clients.size());
  for (const auto& [player, s] : seqs) {
    CHECK(s.size() == 3);
    CHECK(std::is_sorted(s.begin(), s.end()));
  }
  CHECK(t.server->rejects()[Reject::unknown_session] == 0);
  CHECK(t.server->inbox_datagrams() == 0);

  // One job run alone applies the datagrams of its shard's sessions, and nobody else's.
  queue_inputs();
  const auto again = t.server->inbox_jobs();
  REQUIRE(again.size() >= 2);
  const unsigned ran = again[1]->shard();
  again[1]->run(scratch);
  t.server->apply_inbox();
  std::set<std::uint32_t> applied, of_shard;
  for (const auto& in : t.server->take_inputs()) applied.insert(in.player_id);
  for (const auto& [player, shard] : shard_of_player)
    if (shard == ran) of_shard.insert(player);
  CHECK(!applied.empty());
  CHECK(applied == of_shard);
  CHECK(t.server->rejects()[Reject::unknown_session] == 0);
}

TEST_CASE("Server jobs: a queued datagram is screened in its job: another address, or a session gone",
          "[protocol][threads]") {
  TwoRooms t;
  auto& ann = t.add("ann");
  auto& bob = t.add("bob");
  REQUIRE(t.connect_all());
  t.server->take_inputs();
  ann.send_input({1, 0, 0, false}, t.now);
  bob.send_input({0, 1, 0, false}, t.now);
  t.now += 1;
  ann.update(t.now);
  bob.update(t.now);
  // ann's datagram from bob's address, and bob's own, queued; then bob is kicked before the jobs run.
  const auto from_ann = ann.take_datagrams(), from_bob = bob.take_datagrams();
  REQUIRE(!from_ann.empty());
  REQUIRE(!from_bob.empty());
  for (const auto& d : from_ann) t.server->receive_later(t.addresses[1], d, t.now);
  for (const auto& d : from_bob) t.server->receive_later(t.addresses[1], d, t.now);
  CHECK(t.server->rejects()[Reject::address_mismatch] == 0);  // not screened yet: only its sender was
  t.server->kick(bob.welcome()->player_id, ErrorCode::kicked, "bye", t.now);
  std::vector<std::uint8_t> scratch;
  for (InboxJob* job : t.server->inbox_jobs()) job->run(scratch);
  t.server->apply_inbox();
  CHECK(t.server->take_inputs().empty());
  CHECK(t.server->rejects()[Reject::address_mismatch] == from_ann.size());
  CHECK(t.server->rejects()[Reject::unknown_session] == from_bob.size());
}

TEST_CASE("Server jobs: a room's snapshot job holds its room's connected sessions only", "[protocol][threads]") {
  TwoRooms t;
  auto& ann = t.add("ann");
  auto& bob = t.add("bob");
  auto& cid = t.add("cid");
  REQUIRE(t.connect_all());

  const auto& rooms = t.server->connected_by_room();
  REQUIRE(rooms.size() == 2);
  std::size_t in_rooms = 0;
  for (const auto& [room, members] : rooms) in_rooms += members.size();
  CHECK(in_rooms == 3);
  // Admitted in turn: ann and cid in room 1, bob in room 2.
  const auto room_of = [&](const ClientEndpoint& c) { return t.server->session_info(c.welcome()->player_id)->room; };
  CHECK(room_of(ann) == 1);
  CHECK(room_of(cid) == 1);
  CHECK(rooms.at(1).size() == 2);
  CHECK(rooms.at(2).size() == 1);

  // One room's snapshot goes to its own sessions, into its lane; the other room's get none.
  const std::uint32_t bob_room = room_of(bob);
  SendLane lane;
  const auto snap = std::make_shared<const Snapshot>(quantize(Snapshot{}));
  rooms.at(bob_room).send_snapshot(snap, t.now, lane);
  REQUIRE(lane.out.size() == rooms.at(bob_room).size());
  for (const auto& o : lane.out) CHECK(o.to == t.addresses[1]);
  CHECK(t.server->take_datagrams().empty());  // nothing of the lane until adopted
  t.server->adopt(lane);
  CHECK(t.server->take_datagrams().size() == 1);

  // Made again when a session goes: cid's bye leaves ann alone in room 1.
  cid.disconnect(t.now);
  t.step(false);
  const auto& after = t.server->connected_by_room();
  REQUIRE(after.size() == 2);
  CHECK(after.at(1).size() == 1);
  CHECK(after.at(2).size() == 1);
}

TEST_CASE("Server jobs: a room's timer job keeps its own sessions alive, the ends settled in room order",
          "[protocol][threads]") {
  TwoRooms t;
  auto& ann = t.add("ann");
  auto& bob = t.add("bob");
  auto& cid = t.add("cid");
  REQUIRE(t.connect_all());
  for (auto* c : {&ann, &bob, &cid}) c->send_input({0, 1, 0, false}, t.now);  // each played: its seat is held
  t.step(false);
  t.server->take_events();
  t.server->take_datagrams();

  // A heartbeat later, only room 2's job runs: bob (room 2) gets one, ann and cid none.
  t.now += t.config.heartbeat_ms;
  auto jobs = t.server->timer_jobs(t.now);
  REQUIRE(jobs.size() == 2);
  jobs[1].run();
  CHECK(t.server->take_datagrams().empty());  // in the job's lane until settled
  t.server->settle_timers(t.now);
  auto out = t.server->take_datagrams();
  REQUIRE(out.size() == 1);
  CHECK(out[0].to == t.addresses[1]);
  CHECK(t.server->take_events().empty());

  // Silent past the time-out (the server called every 100 ms: a longer gap would be its
  // own stall): the jobs run last first, the time-outs come out in room order (ann and
  // cid in room 1, then bob), each once.
  const std::uint64_t quiet_from = t.now - t.config.heartbeat_ms;
  while (t.now + 100 < quiet_from + t.config.timeout_ms) {
    t.now += 100;
    t.server->update(t.now);
  }
  REQUIRE(t.server->connected_players().size() == 3);
  t.now = quiet_from + t.config.timeout_ms;
  jobs = t.server->timer_jobs(t.now);
  REQUIRE(jobs.size() == 2);
  for (auto it = jobs.rbegin(); it != jobs.rend(); ++it) it->run();
  t.server->settle_timers(t.now);
  const auto events = t.server->take_events();
  std::vector<std::uint32_t> dropped;
  for (const auto& e : events) {
    CHECK(e.kind == ServerEvent::Kind::disconnected);
    CHECK(e.reason == "timeout");
    dropped.push_back(e.player_id);
  }
  const auto id = [](const ClientEndpoint& c) { return c.welcome()->player_id; };
  CHECK(dropped == std::vector<std::uint32_t>{id(ann), id(cid), id(bob)});
  CHECK(t.server->connected_players().empty());
  CHECK(t.server->timer_jobs(t.now).empty());  // nobody connected: no job
  t.server->settle_timers(t.now);
  CHECK(t.server->sessions().size() == 3);  // their seats held for the reconnect window
}

TEST_CASE("Server jobs: a room's sessions with one base share one encoding, each client decodes its own",
          "[protocol][threads]") {
  TwoRooms t;
  auto& ann = t.add("ann");
  t.add("bob");
  auto& cid = t.add("cid");
  t.add("dee");
  auto& eve = t.add("eve");
  REQUIRE(t.connect_all());
  const RoomSessions& room = t.server->connected_by_room().at(1);  // ann, cid and eve
  REQUIRE(room.size() == 3);

  const auto snapshot_at = [](std::uint32_t tick, double x) {
    Snapshot s;
    s.tick = tick;
    s.phase = Phase::play;
    s.balls.push_back(BallState{7, x, 2.0, 0.5, -0.25, 0.5, 1.0, BallKind::enemy, 0});
    return std::make_shared<const Snapshot>(quantize(s));
  };
  const auto deliver = [&](const SendLane& lane, const std::vector<ClientEndpoint*>& to) {
    for (const auto& o : lane.out)
      for (std::size_t i = 0; i < t.clients.size(); ++i)
        if (t.addresses[i] == o.to && std::find(to.begin(), to.end(), t.clients[i].get()) != to.end())
          t.clients[i]->receive(o.bytes, t.now);
  };

  // The first snapshot: nobody has a base, one full encoding for all three.
  SendLane lane;
  const auto first = snapshot_at(1000, 10.0);
  room.send_snapshot(first, t.now, lane);
  CHECK(lane.encoded_used == 1);
  REQUIRE(lane.out.size() == 3);
  // Each datagram sealed for its own session: three different byte strings.
  CHECK(lane.out[0].bytes != lane.out[1].bytes);
  CHECK(lane.out[1].bytes != lane.out[2].bytes);
  deliver(lane, {&ann, &cid});  // eve's is lost
  REQUIRE(ann.latest_snapshot() != nullptr);
  CHECK(*ann.latest_snapshot() == *first);
  // ann and cid acknowledge it with their next input.
  ann.send_input({1, 0, 0, false}, t.now);
  cid.send_input({0, 1, 0, false}, t.now);
  t.step(false);

  // The second: a delta against the first for ann and cid (encoded once), a full one for
  // eve; every client rebuilds exactly what the server sent.
  SendLane next;
  const auto second = snapshot_at(1005, 10.5);
  room.send_snapshot(second, t.now, next);
  CHECK(next.encoded_used == 2);
  REQUIRE(next.out.size() == 3);
  deliver(next, {&ann, &cid, &eve});
  for (ClientEndpoint* c : {&ann, &cid, &eve}) {
    REQUIRE(c->latest_snapshot() != nullptr);
    CHECK(*c->latest_snapshot() == *second);
  }
  // ann's and cid's datagrams carry the same parts (sealed apart); eve's, full, differ.
  const auto size_to = [&](const ClientEndpoint& c) {
    for (std::size_t i = 0; i < t.clients.size(); ++i)
      if (t.clients[i].get() == &c)
        for (const auto& o : next.out)
          if (o.to == t.addresses[i]) return o.bytes.size();
    return std::size_t{0};
  };
  CHECK(size_to(ann) == size_to(cid));
  CHECK(size_to(eve) != size_to(ann));
}
