// A player's own profile requests (issue 41, PROTOCOL.md 4.7c): the board read from a real
// SQLite store (10 000 profiles, hostile names cleaned, the rank), and `cmd top` / `cmd
// forget` from real protocol clients against GameHost with a real profile writer: the
// answer comes from the writer's thread a tick or more later, a guest gets rows and no
// rank, a forget erases the profile and its results, one request at a time.
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "../../support/host_rig.hpp"
#include "../../support/temp_dir.hpp"
#include "app/profile_requests.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/identity.hpp"
#include "fts/protocol/snapshot_delta.hpp"

using namespace fts;
using protocol::ClientState;
using protocol::CommandOp;

namespace {

using test::TempDir;

std::string fp_of(int i) {
  char buf[33];
  std::snprintf(buf, sizeof buf, "%032x", i + 1);
  return buf;
}

profiles::MatchResult result(int i, const std::string& fp, const std::string& name, std::int64_t level,
                             std::int64_t coins) {
  profiles::MatchResult r;
  r.key = "k" + std::to_string(i);
  r.fingerprint = fp;
  r.name = name;
  r.ended_unix_s = 1000 + i;
  r.level = level;
  r.coins = coins;
  return r;
}

std::unique_ptr<profiles::Store> open_ok(const std::string& url) {
  auto r = profiles::Store::open(url);
  if (auto* e = std::get_if<std::string>(&r)) FAIL("open: " << *e);
  return std::move(std::get<std::unique_ptr<profiles::Store>>(r));
}

// Names a shared database may hold that no hello would have let in.
const std::vector<std::string> kHostile = {
    "\x1b[2J\x1b]0;pwned\x07",              // CSI, OSC, BEL
    "\xe6\x97\xa5\xe6\x9c\xac\xe8\xaa\x9e-a-very-long-name-indeed",  // UTF-8 and too long
    "",                                      // nothing
    "  \t  ",                                // nothing printable
    "\xc2\x9b" "31m\x7f\x08",                // C1 CSI, DEL, BS
    std::string("nul\0byte", 8),
};

}  // namespace

TEST_CASE("Profile board: 10 000 profiles, hostile names cleaned, the rank, fast", "[server][profiles][board]") {
  TempDir d;
  auto store = open_ok((d.path / "p.sqlite").string());
  std::vector<profiles::Write> batch;
  for (int i = 0; i < 10'000; ++i) {
    const std::string fp = fp_of(i);
    // The first few are the best, under hostile names; everyone else level 1..40.
    const bool hostile = i < static_cast<int>(kHostile.size());
    const std::string name = hostile ? kHostile[static_cast<std::size_t>(i)] : "p" + std::to_string(i);
    batch.push_back(profiles::Seen{fp, name, 1000});
    batch.push_back(result(i, fp, name, hostile ? 100 - i : 1 + i % 40, i));
  }
  store->write(batch);

  server::BoardCache cache;
  const auto t0 = std::chrono::steady_clock::now();
  const protocol::Leaderboard b = server::read_board(*store, cache, 1, fp_of(5000));
  const auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  WARN("read_board over 10 000 profiles: " << ms << " ms (cold cache)");
  CHECK(ms < 500);  // an index: a few ms, far less than this bound (ASan build)

  REQUIRE(b.top.size() == protocol::kBoardRows);
  CHECK(b.of == 10'000);
  for (std::size_t i = 0; i < b.top.size(); ++i) {
    INFO("row " << i << " " << b.top[i].name);
    CHECK(b.top[i].rank == i + 1);
    CHECK(protocol::name_problem(b.top[i].name).empty());  // 1..16 printable ASCII
  }
  CHECK(b.top[0].name == "[2J]0;pwned");
  CHECK(b.top[1].name == "\?\?\?-a-very-long-");
  CHECK(b.top[2].name == "?");
  CHECK(b.top[3].name == "?");
  CHECK(b.top[4].name == "?31m");
  CHECK(b.top[5].name == "nulbyte");
  CHECK(b.top[0].level == 100);
  // Player 5000 reached level 1 + 5000 % 40 = 1 with 5000 coins: behind every higher
  // level and every level-1 player with more coins.
  CHECK(b.best == 1);
  CHECK(b.best_coins == 5000);
  int ahead = 0;
  for (int i = 0; i < 10'000; ++i) {
    const std::int64_t level = i < static_cast<int>(kHostile.size()) ? 100 - i : 1 + i % 40;
    if (level > 1 || (level == 1 && i > 5000)) ++ahead;
  }
  CHECK(b.rank == static_cast<std::uint32_t>(ahead + 1));
  // A guest: the rows, no rank.
  const auto t1 = std::chrono::steady_clock::now();
  const protocol::Leaderboard g = server::read_board(*store, cache, 1, "");
  const double cached_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
  WARN("read_board, cached rows: " << cached_ms << " ms");
  CHECK(g.top == b.top);
  CHECK(g.rank == 0);
  CHECK(g.best == 0);
  // It goes on the wire as it is, in one datagram.
  for (auto enc : {protocol::Encoding::json, protocol::Encoding::msgpack}) {
    protocol::Leaderboard w = b;
    w.cmd = 9;
    CHECK(protocol::payload_bytes(enc, {w}) <= protocol::kMaxPayloadBytes);
    const auto back = protocol::decode_payload(enc, protocol::encode_payload(enc, {w}));
    REQUIRE(back.ok());
    CHECK(std::get<protocol::Leaderboard>(back->at(0)) == w);
  }
}

namespace {

struct ProfileRig : test::HostRig {
  TempDir dir;
  std::unique_ptr<profiles::Writer> writer;
  explicit ProfileRig(bool with_profiles = true) {
    options.seed = 3;
    options.max_players = 4;
    start();
    if (!with_profiles) return;
    profiles::WriterConfig cfg;
    cfg.url = (dir.path / "p.sqlite").string();
    cfg.spool_dir = dir.path / "spool";
    writer = std::make_unique<profiles::Writer>(cfg);
    REQUIRE(writer->spool_error().empty());
    host->use_profiles(writer.get(), [] { return std::int64_t{5000}; });
  }
  ~ProfileRig() { host.reset(); }  // before the writer it hands results to
  protocol::ClientEndpoint& player(const std::string& name, std::optional<protocol::Identity> id) {
    protocol::ClientConfig c;
    c.name = name;
    c.identity = id;
    auto& client = connect(c);
    for (int i = 0; i < 50 && client.state() == ClientState::connecting; ++i) tick();
    REQUIRE(client.state() == ClientState::connected);
    return client;
  }
  // Ticks until the command's result comes (the writer's thread answers: a wall-clock
  // deadline), keeping the boards that came with it.
  protocol::Result answer(protocol::ClientEndpoint& c, std::uint32_t rid, std::vector<protocol::Leaderboard>* boards) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
      tick();
      for (auto& b : c.take_boards())
        if (boards) boards->push_back(b);
      for (auto& r : c.take_results())
        if (r.command_rid == rid) return r;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    FAIL("no result for command " << rid);
    return {};
  }
};

protocol::Identity identity(std::uint8_t n) {
  std::array<std::uint8_t, protocol::kIdentitySeedBytes> seed{};
  seed.fill(n);
  return protocol::identity_from_seed(seed);
}

}  // namespace

TEST_CASE("Profile requests: top answers with the board and the rank - a guest gets no rank",
          "[server][profiles][board]") {
  ProfileRig rig;
  const auto ann = identity(1), bob = identity(2);
  rig.writer->push(result(1, protocol::fingerprint(bob), "bob", 7, 300));
  rig.writer->push(result(2, protocol::fingerprint(ann), "ann", 4, 100));
  REQUIRE(rig.writer->flush());
  auto& a = rig.player("ann", ann);
  auto& g = rig.player("guest", std::nullopt);

  std::vector<protocol::Leaderboard> boards;
  const auto rid = a.send_command(CommandOp::top, 0, rig.now);
  const auto r = rig.answer(a, rid, &boards);
  CHECK(r.ok);
  CHECK(r.code == "ok");
  for (int i = 0; i < 3 && boards.empty(); ++i) rig.tick();
  for (auto& b : a.take_boards()) boards.push_back(b);
  REQUIRE(boards.size() == 1);
  const protocol::Leaderboard& b = boards[0];
  CHECK(b.cmd == rid);
  CHECK(b.of == 2);
  REQUIRE(b.top.size() == 2);
  CHECK(b.top[0] == protocol::BoardRow{1, "bob", 7, 300});
  CHECK(b.top[1] == protocol::BoardRow{2, "ann", 4, 100});
  CHECK(b.rank == 2);
  CHECK(b.best == 4);
  CHECK(b.best_coins == 100);

  boards.clear();
  const auto grid = g.send_command(CommandOp::top, 0, rig.now);
  CHECK(rig.answer(g, grid, &boards).ok);
  for (int i = 0; i < 3 && boards.empty(); ++i) rig.tick();
  for (auto& x : g.take_boards()) boards.push_back(x);
  REQUIRE(boards.size() == 1);
  CHECK(boards[0].top.size() == 2);
  CHECK(boards[0].rank == 0);
  CHECK(boards[0].best == 0);

  // One request at a time: a second one while the first is unanswered is busy.
  rig.now += server::ProfileRequests::kMinIntervalMs;
  const auto r1 = a.send_command(CommandOp::top, 0, rig.now);
  const auto r2 = a.send_command(CommandOp::top, 0, rig.now);
  std::vector<protocol::Result> got;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (got.size() < 2 && std::chrono::steady_clock::now() < deadline) {
    rig.tick();
    for (auto& x : a.take_results()) got.push_back(x);
  }
  REQUIRE(got.size() == 2);
  for (const auto& x : got) {
    if (x.command_rid == r1) CHECK(x.code == "ok");
    if (x.command_rid == r2) CHECK(x.code == "busy");
  }
}

TEST_CASE("Profile requests: forget erases the identity's profile - a guest has none to forget",
          "[server][profiles][forget]") {
  ProfileRig rig;
  const auto ann = identity(3);
  const std::string fp = protocol::fingerprint(ann);
  rig.writer->push(result(1, fp, "ann", 4, 100));
  REQUIRE(rig.writer->flush());
  auto& a = rig.player("ann", ann);
  auto& g = rig.player("guest", std::nullopt);

  const auto grid = g.send_command(CommandOp::forget, 0, rig.now);
  const auto gr = rig.answer(g, grid, nullptr);
  CHECK_FALSE(gr.ok);
  CHECK(gr.code == "guest");

  const auto rid = a.send_command(CommandOp::forget, 0, rig.now);
  const auto r = rig.answer(a, rid, nullptr);
  CHECK(r.ok);
  CHECK(r.message.find("erased") != std::string::npos);
  auto store = open_ok((rig.dir.path / "p.sqlite").string());
  CHECK_FALSE(store->profile(fp).has_value());
  CHECK(store->results() == 0);
  // Its board has no rank for it any more.
  rig.now += server::ProfileRequests::kMinIntervalMs;
  std::vector<protocol::Leaderboard> boards;
  const auto trid = a.send_command(CommandOp::top, 0, rig.now);
  CHECK(rig.answer(a, trid, &boards).ok);
  for (int i = 0; i < 3 && boards.empty(); ++i) rig.tick();
  for (auto& x : a.take_boards()) boards.push_back(x);
  REQUIRE(boards.size() == 1);
  CHECK(boards[0].rank == 0);
  CHECK(boards[0].of == 0);
}

TEST_CASE("Profile requests: one at a time, one a second per player", "[server][profiles][board]") {
  server::ProfileRequests r;
  CHECK(r.may_ask(1, 5000));
  CHECK_FALSE(r.may_ask(1, 5999));  // within the second
  CHECK(r.may_ask(2, 5999));        // another player
  CHECK(r.may_ask(1, 6000));
  r.drop(1);                        // a new session starts afresh
  CHECK(r.may_ask(1, 6001));
}

TEST_CASE("Profile requests: a server without profiles says so", "[server][profiles][board]") {
  ProfileRig rig(false);
  auto& a = rig.player("ann", identity(4));
  for (const auto op : {CommandOp::top, CommandOp::forget}) {
    const auto rid = a.send_command(op, 0, rig.now);
    const auto r = rig.answer(a, rid, nullptr);
    CHECK_FALSE(r.ok);
    CHECK(r.code == "no_profiles");
  }
}
