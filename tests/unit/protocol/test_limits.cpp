// Abuse bounds (issue 12): queue caps that drop the session, results batched into the
// next update, datagram rates per session and per host. Time is stepped by hand.
#include <catch2/catch.hpp>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "fts/sim/items.hpp"
#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

// One connected client; `raw` sends datagrams on its session as a script would.
struct Flooder {
  Harness h;
  Peer* peer = nullptr;
  std::uint32_t session = 0;
  std::uint32_t player = 0;
  std::uint16_t sequence = 1000;

  explicit Flooder(ServerConfig config = test_server_config()) : h(std::move(config)) {
    peer = &h.add_client(ClientConfig{});
    peer->client.connect(h.now);
    REQUIRE(h.run_until([&] { return peer->client.state() == ClientState::connected; }, 1000));
    player = peer->client.welcome()->player_id;
    h.server.take_events();
    peer->client.send_input({0, 0, 0, false}, h.now);
    auto out = peer->client.take_datagrams();
    REQUIRE(!out.empty());
    session = read_header(out[0])->session;
  }

  void raw(std::vector<Message> messages) {
    Header hd;
    hd.session = session;
    hd.sequence = ++sequence;
    h.server.receive(peer->address, seal_as(peer->client, hd, messages), h.now);
  }

  bool released_for(const std::string& reason) {
    for (const auto& e : h.server.take_events())
      if (e.kind == ServerEvent::Kind::released && e.player_id == player && e.reason == reason) return true;
    return false;
  }

  std::vector<Error> errors_sent() {
    std::vector<Error> out;
    for (const auto& o : h.server.take_datagrams()) {
      auto d = peek(peer->client, o.bytes);
      REQUIRE(d);
      for (const auto& m : d->messages)
        if (const auto* e = std::get_if<Error>(&m)) out.push_back(*e);
    }
    return out;
  }
};

std::size_t results_in(const ClientEndpoint& client, const std::vector<Outgoing>& out) {
  std::size_t n = 0;
  for (const auto& o : out) {
    auto d = peek(client, o.bytes);
    REQUIRE(d);
    for (const auto& m : d->messages) n += std::holds_alternative<Result>(m) ? 1 : 0;
  }
  return n;
}

}  // namespace

TEST_CASE("Limits: a token bucket refills with the time passed in", "[protocol][limits]") {
  TokenBucket b(10, 3, 1000);
  CHECK(b.take(1000));
  CHECK(b.take(1000));
  CHECK(b.take(1000));
  CHECK_FALSE(b.take(1000));   // burst spent
  CHECK_FALSE(b.take(1099));   // 0.99 tokens
  CHECK(b.take(1100));         // one more after 100 ms at 10/s
  CHECK_FALSE(b.full(1100));
  CHECK(b.full(1400));         // 3 tokens after 300 ms more
  CHECK_FALSE(b.take(900));    // time going backwards gives nothing
}

TEST_CASE("Limits: the host of an address", "[protocol][limits]") {
  CHECK(host_of("192.0.2.7:40000") == "192.0.2.7");
  CHECK(host_of("[::1]:5000") == "[::1]");
  CHECK(host_of("::1") == "::1");
  CHECK(host_of("localhost") == "localhost");
}

TEST_CASE("Limits: each host keeps its own buckets across growth and forgetting", "[protocol][limits]") {
  // A seeded walk over 600 hosts (IPv4 and IPv6), against a reference count of the
  // datagrams each host's bucket let through: a host found again is the same host, a new
  // one starts full, growth past every table size keeps them, forget_quiet drops only
  // the quiet and those come back full.
  AddressLimits::Rates r;
  r.datagrams_per_s = 1;  // refills a token a second: taken tokens show for a while
  r.datagram_burst = 5;
  r.hellos_per_s = r.hello_burst = r.takeovers_per_s = r.takeover_burst = 1;
  r.code_misses_per_min = r.code_miss_burst = 1;
  r.max_hosts = 1000;
  AddressLimits limits(r);
  std::vector<std::string> names;
  for (int i = 0; i < 300; ++i) names.push_back("10." + std::to_string(i / 250) + "." + std::to_string(i % 250) + ".7");
  for (int i = 0; i < 300; ++i) names.push_back("[2001:db8::" + std::to_string(i) + "]");
  std::map<std::string, int> taken;  // tokens taken since the host was (re)made
  std::uint64_t seed = 12345;
  const auto next = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<std::size_t>(seed >> 33);
  };
  const std::uint64_t now = 1000;
  for (int step = 0; step < 4000; ++step) {
    const std::string& h = names[next() % names.size()];
    AddressLimits::Host* host = limits.of(h, now);
    REQUIRE(host != nullptr);
    const bool expect = taken[h] < 5;  // no time passes: only the burst
    REQUIRE(host->datagrams.take(now) == expect);
    if (expect) ++taken[h];
    REQUIRE(limits.of(h, now) == host);  // the same host again
  }
  CHECK(limits.tracked() == taken.size());
  // Ten seconds on, every bucket is full again except those taken from now: those stay.
  const std::uint64_t later = now + 10000;
  std::set<std::string> busy;
  for (std::size_t i = 0; i < names.size(); i += 7) {
    busy.insert(names[i]);
    REQUIRE(limits.of(names[i], later)->datagrams.take(later));
  }
  limits.forget_quiet(later);
  CHECK(limits.tracked() == busy.size());
  for (const auto& h : busy) {  // kept: the token taken is still missing (burst 5, 4 left)
    AddressLimits::Host* host = limits.of(h, later);
    for (int i = 0; i < 4; ++i) REQUIRE(host->datagrams.take(later));
    CHECK_FALSE(host->datagrams.take(later));
  }
  CHECK(limits.tracked() == busy.size());
  AddressLimits::Host* back = limits.of(names[1], later);  // forgotten: made again, full
  for (int i = 0; i < 5; ++i) REQUIRE(back->datagrams.take(later));
  CHECK(limits.tracked() == busy.size() + 1);
  // Past max_hosts a new host is not tracked; a tracked one still is.
  r.max_hosts = 2;
  AddressLimits small(r);
  CHECK(small.of("a", now) != nullptr);
  CHECK(small.of("b", now) != nullptr);
  CHECK(small.of("c", now) == nullptr);
  CHECK(small.of("a", now) == small.of("a", now));
}

TEST_CASE("Limits: results ride the next update, batched", "[protocol][limits]") {
  Flooder f;
  f.h.server.take_datagrams();
  for (std::uint32_t rid = 1; rid <= 5; ++rid) f.h.server.send_result(f.player, rid, ResultCode::ok, "done", f.h.now);
  CHECK(f.h.server.take_datagrams().empty());  // nothing sent per result
  f.h.server.update(f.h.now + 1);
  auto first = f.h.server.take_datagrams();
  CHECK(first.size() == 1);
  CHECK(results_in(f.peer->client, first) == 3);
  f.h.server.update(f.h.now + 2);
  auto second = f.h.server.take_datagrams();
  CHECK(second.size() == 1);
  CHECK(results_in(f.peer->client, second) == 2);
}

TEST_CASE("Limits: unacknowledged results past the cap drop the session", "[protocol][limits]") {
  ServerConfig config = test_server_config();
  config.max_pending_results = 10;
  Flooder f(config);
  f.h.server.take_datagrams();
  for (std::uint32_t rid = 1; rid <= 10; ++rid) f.h.server.send_result(f.player, rid, ResultCode::ok, "done", f.h.now);
  CHECK(f.h.server.connected_players().size() == 1);
  CHECK(f.h.server.rejects()[Reject::overflow] == 0);
  f.h.server.send_result(f.player, 11, ResultCode::ok, "done", f.h.now);  // the 11th, never acknowledged
  CHECK(f.h.server.connected_players().empty());
  CHECK(f.h.server.rejects()[Reject::overflow] == 1);
  CHECK(f.released_for("overflow"));
  const auto errors = f.errors_sent();
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].code == "overflow");
}

TEST_CASE("Limits: commands answered as faulty past the results cap drop the session once", "[protocol][limits]") {
  // Each command's text is over 200 bytes: answered at once (bad_field), never applied; the
  // answers are never acknowledged. The 11th overflows the results in the middle of a
  // datagram: the session is dropped there and nothing after it touches the session.
  ServerConfig config = test_server_config();
  config.max_pending_results = 10;
  Flooder f(config);
  f.h.server.take_datagrams();
  for (std::uint32_t rid = 1; rid <= 15; rid += 3) {
    std::vector<Message> batch;
    for (std::uint32_t i = rid; i < rid + 3; ++i) batch.push_back(Command{i, CommandOp::chat, 0, std::string(201, 'x'), {}});
    f.raw(batch);
  }
  CHECK(f.h.server.rejects()[Reject::bad_field] == 11);
  CHECK(f.h.server.rejects()[Reject::overflow] == 1);
  CHECK(f.h.server.take_commands().empty());
  CHECK(f.h.server.connected_players().empty());
  CHECK(f.released_for("overflow"));
}

TEST_CASE("Limits: acknowledged results never reach the cap", "[protocol][limits]") {
  ServerConfig config = test_server_config();
  config.max_pending_results = 8;  // the client acknowledges every 100 ms at least
  Harness h(config);
  Peer& p = h.add_client(ClientConfig{});
  p.client.connect(h.now);
  REQUIRE(h.run_until([&] { return p.client.state() == ClientState::connected; }, 1000));
  const std::uint32_t player = p.client.welcome()->player_id;
  for (std::uint32_t rid = 1; rid <= 40; ++rid) {
    h.server.send_result(player, rid, ResultCode::ok, "done", h.now);
    h.run_until([] { return false; }, h.now + 25);
  }
  CHECK(h.server.connected_players().size() == 1);
  CHECK(h.server.rejects()[Reject::overflow] == 0);
}

TEST_CASE("Limits: commands past the cap drop the session", "[protocol][limits]") {
  ServerConfig config = test_server_config();
  config.max_pending_commands = 40;
  SECTION("delivered and not answered") {
    Flooder f(config);
    std::vector<Message> batch;
    for (std::uint32_t rid = 1; rid <= 32; ++rid) batch.push_back(Command{rid, CommandOp::buy, 'm', {}, {}});
    f.raw(batch);
    CHECK(f.h.server.rejects()[Reject::overflow] == 0);
    batch.clear();
    for (std::uint32_t rid = 33; rid <= 41; ++rid) batch.push_back(Command{rid, CommandOp::buy, 'm', {}, {}});
    f.raw(batch);
    CHECK(f.h.server.rejects()[Reject::overflow] == 1);
    CHECK(f.h.server.take_commands().empty());  // what it queued is not handed to the game
    CHECK(f.released_for("overflow"));
  }
  SECTION("answered at once, the flood is bounded by the results") {
    Flooder f(config);
    std::uint32_t rid = 1;
    for (int packet = 0; packet < 10 && !f.h.server.connected_players().empty(); ++packet) {
      std::vector<Message> batch;
      for (int i = 0; i < 32; ++i) batch.push_back(Command{rid++, CommandOp::buy, 'm', {}, {}});
      f.raw(batch);
      for (const auto& c : f.h.server.take_commands())
        f.h.server.send_result(c.player_id, c.command.rid, ResultCode::coins, "no", f.h.now);
    }
    CHECK(f.h.server.connected_players().empty());
    CHECK(f.h.server.rejects()[Reject::overflow] == 1);
  }
  SECTION("buffered out of order") {
    Flooder f(config);
    std::vector<Message> batch;
    for (std::uint32_t rid = 2; rid <= 33; ++rid) batch.push_back(Command{rid, CommandOp::buy, 'm', {}, {}});
    f.raw(batch);  // 32 held: rid 1 is missing
    CHECK(f.h.server.take_commands().empty());
    CHECK(f.h.server.rejects()[Reject::overflow] == 0);
    batch.clear();
    for (std::uint32_t rid = 100; rid <= 108; ++rid) batch.push_back(Command{rid, CommandOp::buy, 'm', {}, {}});
    f.raw(batch);
    CHECK(f.h.server.rejects()[Reject::overflow] == 1);
  }
}

TEST_CASE("Limits: a session over its datagram rate is dropped per datagram, counted", "[protocol][limits]") {
  ServerConfig config = test_server_config();
  config.session_datagrams_per_s = 100;
  config.session_datagram_burst = 50;
  Flooder f(config);
  f.h.now += 1000;  // the bucket is full again, whatever the handshake took
  const auto limited = f.h.server.rejects()[Reject::rate_limited];
  std::uint32_t seq = 1;
  std::size_t inputs = 0;
  for (int i = 0; i < 80; ++i) {
    f.raw({Input{0, {InputFrame{seq++, 1, 0, false}}}});
    inputs += f.h.server.take_inputs().size();
  }
  CHECK(inputs == 50);  // the burst
  CHECK(f.h.server.rejects()[Reject::rate_limited] == limited + 30);
  CHECK(f.h.server.sessions().at(0).rate_limited == 30);
  f.h.now += 100;  // 10 more tokens
  for (int i = 0; i < 20; ++i) {
    f.raw({Input{0, {InputFrame{seq++, 1, 0, false}}}});
    inputs += f.h.server.take_inputs().size();
  }
  CHECK(inputs == 60);
  CHECK(f.h.server.connected_players().size() == 1);  // limited, not dropped
}

TEST_CASE("Limits: a host over its datagram rate is refused before any parse", "[protocol][limits]") {
  ServerConfig config = test_server_config();
  config.address_datagrams_per_s = 100;
  config.address_datagram_burst = 20;
  ServerEndpoint server(one_room(config, server));
  const std::vector<std::uint8_t> junk(40, 'x');
  for (int port = 1; port <= 30; ++port) server.receive("198.51.100.9:" + std::to_string(port), junk, 1000);
  CHECK(server.rejects()[Reject::wrong_protocol_id] == 20);
  CHECK(server.rejects()[Reject::rate_limited] == 10);
  server.receive("198.51.100.10:1", junk, 1000);  // another host has its own bucket
  CHECK(server.rejects()[Reject::wrong_protocol_id] == 21);
  server.receive("198.51.100.9:1", junk, 1010);  // one token back after 10 ms
  CHECK(server.rejects()[Reject::wrong_protocol_id] == 22);
}

TEST_CASE("Limits: hosts tracked are bounded and quiet ones forgotten", "[protocol][limits]") {
  ServerConfig config = test_server_config();
  config.address_datagrams_per_s = 10;
  config.address_datagram_burst = 1;
  config.max_tracked_addresses = 2;
  ServerEndpoint server(one_room(config, server));
  const std::vector<std::uint8_t> junk(40, 'x');
  server.receive("10.0.0.1:1", junk, 1000);
  server.receive("10.0.0.2:1", junk, 1000);
  server.receive("10.0.0.1:1", junk, 1000);  // tracked, limited
  CHECK(server.rejects()[Reject::rate_limited] == 1);
  server.receive("10.0.0.3:1", junk, 1000);  // past the bound: not tracked, not limited
  server.receive("10.0.0.3:1", junk, 1000);
  CHECK(server.rejects()[Reject::rate_limited] == 1);
  server.update(2000);  // 10.0.0.1 and .2 are full again: forgotten
  server.receive("10.0.0.3:1", junk, 2000);
  server.receive("10.0.0.3:1", junk, 2000);  // now tracked
  CHECK(server.rejects()[Reject::rate_limited] == 2);
}

TEST_CASE("Limits: a faulty command's answer names what the server takes", "[protocol][limits]") {
  // A buy whose item is no printable character and a chat line over the cap: each is
  // answered at once, and the answer lists the shop's keys (every item, nothing else) and
  // the text's limit, as the tables that read them say.
  Flooder f;
  f.h.server.take_datagrams();
  f.raw({Command{1, CommandOp::buy, '\x01', "", {}}, Command{2, CommandOp::chat, 0, std::string(kMaxTextBytes + 1, 'x'), {}}});
  f.h.server.update(f.h.now);  // the answers go out with the timers
  std::vector<Result> results;
  for (const auto& o : f.h.server.take_datagrams()) {
    auto d = peek(f.peer->client, o.bytes);
    REQUIRE(d);
    for (const auto& m : d->messages)
      if (const auto* r = std::get_if<Result>(&m)) results.push_back(*r);
  }
  REQUIRE(results.size() == 2);
  CHECK(results[0].code == "item");
  const std::string listed = results[0].message.substr(results[0].message.rfind(':') + 1);
  std::size_t keys = 0;
  for (std::size_t i = 0; i < listed.size(); i += 2) {
    CHECK(listed[i] == ' ');
    REQUIRE(i + 1 < listed.size());
    CHECK(fts::sim::item_by_key(listed[i + 1]).has_value());
    ++keys;
  }
  CHECK(keys == fts::sim::kItemCount);
  CHECK(results[1].code == "field");
  CHECK_THAT(results[1].message, Catch::Contains("at most " + std::to_string(kMaxTextBytes) + " bytes"));
  CHECK(f.h.server.take_commands().empty());
}
