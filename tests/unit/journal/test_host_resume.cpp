// GameHost with a journal (issue 15), real protocol clients in memory, time stepped by
// hand: a host that dies is rebuilt from its journal by another host (a new key), and the
// client that comes back with its token finds its player as it was.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>

#include "app/game_host.hpp"
#include "fts/protocol/client.hpp"

using namespace fts;
namespace fs = std::filesystem;

namespace {

struct Link {
  std::unique_ptr<server::GameHost> host;
  protocol::ClientEndpoint client;
  std::uint64_t now = 1000;
  std::string address = "10.0.0.1:5000";

  void tick() {
    client.update(now);
    for (auto& d : client.take_datagrams()) host->receive(address, d, now);
    host->tick(now);
    for (auto& out : host->take_datagrams())
      if (out.to == address) client.receive(out.bytes, now);
    now += 10;
  }
};

protocol::ClientConfig named(const std::string& name, const std::string& token = "") {
  protocol::ClientConfig c;
  c.name = name;
  c.token = token;
  return c;
}

protocol::ServerKey key(std::uint8_t b) {
  protocol::ServerKey k{};
  k.fill(b);
  return k;
}

}  // namespace

TEST_CASE("Host resume: a host rebuilt from the journal takes the player back by token", "[journal][host]") {
  const fs::path dir = fs::temp_directory_path() / ("fts-host-resume-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  server::Options options;
  options.seed = 11;
  sim::MatchConfig config;
  host::JournalConfig jc;
  jc.dir = dir;
  jc.seed = options.seed;
  jc.sync_ms = 5;
  jc.checkpoint_every_ticks = 150;

  Link a{std::make_unique<server::GameHost>(options, config, key(1)), protocol::ClientEndpoint(named("ann"))};
  a.host->journal_to(jc);
  a.client.connect(a.now);
  for (int i = 0; i < 50 && a.client.state() != protocol::ClientState::connected; ++i) a.tick();
  REQUIRE(a.client.state() == protocol::ClientState::connected);
  const std::string token = a.client.welcome()->token;
  const std::uint32_t id = a.client.welcome()->player_id;
  a.client.send_command(protocol::CommandOp::ready, 0, a.now);
  for (int i = 0; i < 400; ++i) {
    a.client.send_input({0, static_cast<std::int8_t>(i % 60 < 30 ? 1 : -1), 0, i % 20 == 0}, a.now);
    a.tick();
  }
  REQUIRE(a.host->match().phase == sim::Phase::playing);
  a.host->journal()->flush();
  const sim::MatchState crashed = a.host->match();
  a.host.reset();  // the process is gone (its journal was synced up to here)

  auto read = host::read_journal(dir, &server::GameHost::wire_event_count);
  REQUIRE(std::holds_alternative<host::ResumedRoom>(read));
  const auto& room = std::get<host::ResumedRoom>(read);
  CHECK(room.damage.empty());
  CHECK(room.state.tick == crashed.tick);
  CHECK(sim::match_hash(room.state) == sim::match_hash(crashed));
  REQUIRE(room.sessions.size() == 1);
  CHECK(room.sessions[0].player == id);
  CHECK(room.sessions[0].verifier != token);

  Link b{std::make_unique<server::GameHost>(options, room.config, key(2)), protocol::ClientEndpoint(named("ann", token))};
  b.now = 50;
  b.host->resume_from(room, b.now);
  b.host->journal_to(jc);  // a new segment after the old ones
  b.tick();
  const sim::Player* p = sim::find_player(b.host->match(), id);
  REQUIRE(p);
  CHECK_FALSE(p->connected);  // away until its client comes back
  b.address = "10.0.0.1:6000";  // a new attempt comes from a new port
  b.client.connect(b.now);
  for (int i = 0; i < 50 && b.client.state() != protocol::ClientState::connected; ++i) b.tick();
  REQUIRE(b.client.state() == protocol::ClientState::connected);
  CHECK(b.client.welcome()->reconnected);
  CHECK(b.client.welcome()->player_id == id);
  b.tick();
  p = sim::find_player(b.host->match(), id);
  REQUIRE(p);
  CHECK(p->connected);
  const sim::Player* before = sim::find_player(crashed, id);
  CHECK(p->eco.coins == before->eco.coins);
  CHECK(p->eco.lives == before->eco.lives);
  CHECK(p->eco.mass == before->eco.mass);
  CHECK(b.host->match().level == crashed.level);
  b.host.reset();
  fs::remove_all(dir);
}
