// Client and server endpoints over in-memory links, time stepped by hand: handshake,
// exactly-once commands, snapshot reconstruction, time-outs, reconnects, refusals.
#include <catch2/catch.hpp>

#include <map>

#include "harness.hpp"
#include "samples.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

ClientConfig client_config(const std::string& name, Encoding enc = Encoding::msgpack) {
  ClientConfig c;
  c.name = name;
  c.encoding = enc;
  return c;
}

Snapshot without_events(Snapshot s) {
  s.events.clear();
  return s;
}

}  // namespace

TEST_CASE("handshake on a perfect link", "[protocol][connection]") {
  for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
    Harness h;
    Peer& p = h.add_client(client_config("ann", enc));
    p.client.connect(h.now);
    REQUIRE(h.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
    REQUIRE(p.client.welcome());
    CHECK(p.client.welcome()->player_id == 1);
    CHECK(p.client.welcome()->token.size() == 32);
    CHECK_FALSE(p.client.welcome()->reconnected);
    const auto events = h.server.take_events();
    REQUIRE(events.size() == 1);
    CHECK(events[0].kind == ServerEvent::Kind::connected);
    CHECK(events[0].name == "ann");
    CHECK(h.server.rejects().total() == 0);
    CHECK(p.client.rejects().total() == 0);
    const auto sessions = h.server.sessions();
    REQUIRE(sessions.size() == 1);
    CHECK(sessions[0].encoding == enc);
  }
}

TEST_CASE("commands exactly once and snapshots exact over 25% loss, 25% dups, 100 ms jitter",
          "[protocol][connection][lossy]") {
  Harness h;
  constexpr int kClients = 4;
  constexpr std::uint32_t kCommands = 30;
  for (int i = 0; i < kClients; ++i) {
    LinkConfig link{0.25, 0.25, 20, 100, static_cast<std::uint64_t>(i + 1)};
    // A frame every tick, each repeated in the next 8 datagrams (the default is 3 since
    // the lean uplink of issue 14, which sends frames on change only).
    ClientConfig config = client_config("bot" + std::to_string(i), i % 2 ? Encoding::json : Encoding::msgpack);
    config.input_redundancy = 8;
    h.add_client(config, link).client.connect(h.now);
  }
  REQUIRE(h.run_until([&] {
    for (auto& p : h.peers)
      if (p->client.state() != ClientState::connected) return false;
    return true;
  }, 10000));
  h.server.take_events();

  std::map<std::uint32_t, std::vector<std::uint32_t>> commands_at_server;  // player -> rids
  std::map<std::uint32_t, std::vector<std::uint32_t>> inputs_at_server;    // player -> seqs
  std::map<std::uint32_t, Snapshot> sent;                                  // tick -> snapshot
  std::vector<std::vector<Result>> results(kClients);
  std::vector<std::uint32_t> sent_commands(kClients, 0), sent_inputs(kClients, 0);
  std::vector<int> snapshots_ok(kClients, 0);
  int snapshot_mismatches = 0;

  Snapshot world = sample_snapshot(kClients, 12, 1);
  const std::uint64_t start = h.now;
  for (std::uint64_t t = start + 10; t < start + 20000; t += 10) {
    h.step(t);
    const bool sending = t < start + 12000;
    for (int i = 0; i < kClients; ++i) {
      auto& c = h.peers[i]->client;
      if (sending) {
        c.send_input({0, 1, -1, false}, t), ++sent_inputs[i];
        if ((t / 10) % 25 == static_cast<std::uint64_t>(i) && sent_commands[i] < kCommands)
          c.send_command(CommandOp::buy, 'm', t), ++sent_commands[i];
      }
      for (auto& r : c.take_results()) results[i].push_back(r);
      for (auto& s : c.take_snapshots()) {
        auto it = sent.find(s.tick);
        if (it != sent.end() && without_events(s) == without_events(quantize(it->second))) ++snapshots_ok[i];
        else ++snapshot_mismatches;
      }
    }
    for (auto& in : h.server.take_inputs()) inputs_at_server[in.player_id].push_back(in.frame.seq);
    for (auto& pc : h.server.take_commands()) {
      commands_at_server[pc.player_id].push_back(pc.command.rid);
      world.players[pc.player_id - 1].coins += 1;  // the state changes with every command
      h.server.send_result(pc.player_id, pc.command.rid, ResultCode::ok, "bought mass", t);
    }
    if (t % 50 == 0) {
      world = advance(world, 5, 0.05);
      sent[world.tick] = world;
      for (auto pid : h.server.connected_players()) h.server.send_snapshot(pid, world, t);
    }
  }

  CHECK(snapshot_mismatches == 0);
  CHECK(h.server.take_events().empty());  // nobody timed out
  for (int i = 0; i < kClients; ++i) {
    CAPTURE(i);
    const std::uint32_t pid = h.peers[i]->client.welcome()->player_id;
    CHECK(sent_commands[i] == kCommands);
    std::vector<std::uint32_t> expected;
    for (std::uint32_t r = 1; r <= kCommands; ++r) expected.push_back(r);
    CHECK(commands_at_server[pid] == expected);  // exactly once, in order
    REQUIRE(results[i].size() == kCommands);
    for (std::uint32_t r = 0; r < kCommands; ++r) CHECK(results[i][r].command_rid == r + 1);
    CHECK(snapshots_ok[i] > 100);
    const auto& seqs = inputs_at_server[pid];
    CHECK(std::adjacent_find(seqs.begin(), seqs.end(), std::greater_equal<>()) == seqs.end());
    CHECK(seqs.size() >= sent_inputs[i] * 95 / 100);  // redundancy covers 25% loss
  }
}

TEST_CASE("time-out, then the slot is held for the reconnect window", "[protocol][connection]") {
  Harness h;
  Peer& p = h.add_client(client_config("ann"));
  p.client.connect(h.now);
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
  p.client.send_input({1, 1, 0, false}, h.now);  // a player, not a probe (6: slots)
  h.step(h.now + 5);
  h.server.take_events();
  // The link goes silent both ways.
  p.up = LossyLink({1.0, 0, 0, 0, 1});
  p.down = LossyLink({1.0, 0, 0, 0, 2});
  const std::uint64_t silent_from = h.now;
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::timed_out; }, silent_from + 11000));
  h.run_until([] { return false; }, h.now + 50);  // the server heard the input last: it times out a bit later
  auto events = h.server.take_events();
  REQUIRE(events.size() == 1);
  CHECK(events[0].kind == ServerEvent::Kind::disconnected);
  CHECK(events[0].reason == "timeout");
  CHECK(h.now - silent_from >= 10000);
  CHECK(h.server.sessions().size() == 1);
  h.run_until([&] { return false; }, silent_from + 10000 + 60000 + 100);
  events = h.server.take_events();
  REQUIRE(events.size() == 1);
  CHECK(events[0].kind == ServerEvent::Kind::released);
  CHECK(h.server.sessions().empty());
}

TEST_CASE("a token takes the player back from another address", "[protocol][connection]") {
  Harness h;
  Peer& a = h.add_client(client_config("ann"));
  a.client.connect(h.now);
  REQUIRE(h.run_until([&] { return a.client.state() == ClientState::connected; }, 1000));
  const Welcome first = *a.client.welcome();
  h.server.take_events();

  ClientConfig again = client_config("ann");
  again.token = first.token;
  Peer& b = h.add_client(again, {}, "10.9.9.9:6000");
  b.client.connect(h.now);
  REQUIRE(h.run_until([&] { return b.client.state() == ClientState::connected; }, h.now + 1000));
  CHECK(b.client.welcome()->player_id == first.player_id);
  CHECK(b.client.welcome()->reconnected);
  const auto events = h.server.take_events();
  REQUIRE(events.size() == 1);
  CHECK(events[0].kind == ServerEvent::Kind::reconnected);
  CHECK(events[0].player_id == first.player_id);
  // The old process is told (not left to time out), and its old session is dead.
  REQUIRE(h.run_until([&] { return a.client.state() == ClientState::refused; }, h.now + 300));
  CHECK(a.client.error()->code == "taken_over");
  CHECK(h.server.sessions().size() == 1);
}

TEST_CASE("an unknown token is refused with a reason", "[protocol][connection]") {
  Harness h;
  ClientConfig c = client_config("ann");
  c.token = std::string(32, 'e');
  Peer& p = h.add_client(c);
  p.client.connect(h.now);
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::refused; }, 1000));
  CHECK(p.client.error()->code == "bad_token");
  CHECK(h.server.rejects()[Reject::bad_token] == 1);
  CHECK(h.server.sessions().empty());
}

TEST_CASE("bye disconnects cleanly", "[protocol][connection]") {
  Harness h;
  Peer& p = h.add_client(client_config("ann"));
  p.client.connect(h.now);
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
  h.server.take_events();
  p.client.disconnect(h.now, "quit");
  h.run_until([&] { return false; }, h.now + 100);
  const auto events = h.server.take_events();
  REQUIRE(events.size() == 1);
  CHECK(events[0].kind == ServerEvent::Kind::disconnected);
  CHECK(events[0].reason == "quit");
  CHECK(h.server.connected_players().empty());
}

TEST_CASE("the player after the last slot gets a clear refusal", "[protocol][connection]") {
  ServerConfig config = test_server_config();
  config.max_players = 2;
  Harness h(config);
  for (int i = 0; i < 3; ++i) h.add_client(client_config("p" + std::to_string(i))).client.connect(h.now);
  h.run_until([&] { return false; }, 1000);
  CHECK(h.peers[0]->client.state() == ClientState::connected);
  CHECK(h.peers[1]->client.state() == ClientState::connected);
  REQUIRE(h.peers[2]->client.state() == ClientState::refused);
  CHECK(h.peers[2]->client.error()->code == "server_full");
  CHECK(h.peers[2]->client.error()->message.find("full") != std::string::npos);
}

TEST_CASE("a wrong protocol version gets a clear error", "[protocol][connection]") {
  Harness h;
  ClientConfig c = client_config("old");
  c.version = kProtocolVersion + 1;
  Peer& p = h.add_client(c);
  p.client.connect(h.now);
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::refused; }, 1000));
  CHECK(p.client.error()->code == "version");
  CHECK(p.client.error()->message.find("version " + std::to_string(kProtocolVersion)) != std::string::npos);
  CHECK(h.server.rejects()[Reject::bad_version] >= 1);
  CHECK(h.server.sessions().empty());
}

TEST_CASE("kick and shutdown reach the client", "[protocol][connection]") {
  Harness h;
  Peer& p = h.add_client(client_config("ann"));
  p.client.connect(h.now);
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
  h.server.shutdown(h.now);
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::refused; }, h.now + 100));
  CHECK(p.client.error()->code == "shutdown");
  CHECK(h.server.sessions().empty());
}
