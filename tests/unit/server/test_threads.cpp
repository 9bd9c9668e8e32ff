// Issue 29: rooms stepped on several threads play exactly as on one. The same twelve
// real protocol clients (six rooms of two), the same script, time stepped by hand, with
// 1, 2 and 3 threads: every room's record is the same byte for byte, every client gets
// the same snapshots, and the host's datagrams leave in the same order (to, size).
#include <catch2/catch.hpp>

#include <algorithm>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "../../support/host_rig.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/snapshot_delta.hpp"

using namespace fts;

namespace {

struct Played {
  std::map<std::string, std::string> records;  // file name -> bytes
  std::vector<std::vector<std::uint8_t>> snapshots;  // every client's, in order
  std::vector<std::string> datagrams;                 // "to size" in the order sent
  std::vector<std::uint64_t> jobs;                    // per thread
};

Played play(unsigned threads) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() /
                       ("fts-threads-" + std::to_string(::getpid()) + "-" + std::to_string(threads));
  fs::remove_all(dir);
  fs::create_directories(dir);
  test::HostRig rig;
  rig.options.seed = 29;
  rig.options.max_players = 2;
  rig.options.max_per_address = 16;
  rig.options.threads = threads;
  rig.start();
  rig.host->record_dir(dir.string(), "test");
  for (int i = 0; i < 12; ++i) rig.add("p" + std::to_string(i));
  REQUIRE(rig.connect_all());
  Played p;
  rig.sent_log = &p.datagrams;
  for (int t = 0; t < 1500; ++t) {
    for (std::size_t i = 0; i < rig.clients.size(); ++i) {
      auto& c = *rig.clients[i];
      if (t % 100 == static_cast<int>(i)) c.send_command(protocol::CommandOp::ready, 0, rig.now);
      if (t % 7 == 0)
        c.send_input({0, static_cast<std::int8_t>((t / 40 + static_cast<int>(i)) % 3 - 1),
                      static_cast<std::int8_t>((t / 30 + static_cast<int>(i)) % 3 - 1), t % 90 == 0},
                     rig.now);
      if (t % 211 == static_cast<int>(i)) c.send_command(protocol::CommandOp::buy, 'm', rig.now);
    }
    rig.tick();
    for (auto& c : rig.clients)
      for (auto& s : c->take_snapshots())
        p.snapshots.push_back(
            protocol::encode_payload(protocol::Encoding::msgpack, {protocol::make_snapshot_msg(s, nullptr)}));
  }
  rig.sent_log = nullptr;
  p.jobs = rig.host->workers().jobs_per_thread();
  rig.host.reset();  // the records are flushed and closed
  for (const auto& room : fs::directory_iterator(dir))  // room-<id>/: a journal's segments
    for (const auto& [n, segment] : store::list_segments(room.path())) {
      std::ifstream in(segment, std::ios::binary);
      std::stringstream bytes;
      bytes << in.rdbuf();
      p.records[room.path().filename().string() + "/" + segment.filename().string()] = bytes.str();
    }
  fs::remove_all(dir);
  return p;
}

}  // namespace

TEST_CASE("Threads: a room plays the same, byte for byte, whichever thread stepped it", "[threads][record]") {
  const Played one = play(1);
  REQUIRE(one.records.size() == 12);  // 6 rooms, two segments each (1500 ticks, one every 1000)
  for (const auto& [name, bytes] : one.records) CHECK(bytes.size() > 1000);
  REQUIRE(one.snapshots.size() > 12 * 250);
  for (const unsigned threads : {2u, 3u}) {
    INFO(threads << " threads");
    const Played many = play(threads);
    REQUIRE(many.jobs.size() == threads);
    CHECK(many.records == one.records);
    CHECK(many.snapshots == one.snapshots);
    CHECK(many.datagrams == one.datagrams);
  }
}

TEST_CASE("Threads: the pool runs every job once per run and rethrows a job's exception",
          "[threads]") {
  server::WorkerPool pool(3);
  REQUIRE(pool.threads() == 3);
  std::vector<int> hits(1000, 0);
  std::vector<std::vector<int>> by_slot(pool.threads());  // each thread's own, as scratch is
  for (int round = 0; round < 50; ++round)
    pool.run(hits.size(), [&](std::size_t i, std::size_t slot) {
      ++hits[i];
      by_slot.at(slot).push_back(static_cast<int>(i));
    });
  for (int h : hits) REQUIRE(h == 50);
  std::uint64_t total = 0;
  for (auto n : pool.jobs_per_thread()) total += n;
  CHECK(total == 50 * 1000);
  std::size_t seen = 0;  // every call ran on a slot below threads(), the caller's 0 included
  for (const auto& v : by_slot) seen += v.size();
  CHECK(seen == 50 * 1000);
  CHECK_THROWS_AS(pool.run(10, [](std::size_t i, std::size_t) { if (i == 7) throw std::runtime_error("job 7"); }),
                  std::runtime_error);
  int after = 0;
  pool.run(1, [&](std::size_t, std::size_t) { ++after; });  // still works
  CHECK(after == 1);
  for (std::size_t n : {2, 3, 7, 64}) {  // shares of every size, some empty: each index once
    std::vector<int> once(n, 0);
    pool.run(n, [&](std::size_t i, std::size_t) { ++once.at(i); });
    CHECK(std::count(once.begin(), once.end(), 1) == static_cast<std::ptrdiff_t>(n));
  }
  CHECK(server::WorkerPool(0).threads() == server::WorkerPool::usable_cores());
}

TEST_CASE("Threads: while a pool runs on the endpoint, a serial call is refused by name",
          "[threads]") {
  protocol::ServerConfig config;
  config.admit = [](const protocol::JoinAsk&) {
    protocol::Admission a;
    a.room = 1;
    return a;
  };
  protocol::ServerEndpoint e(config);
  {
    const protocol::ServerEndpoint::ParallelPhase parallel(e);
    if constexpr (protocol::ServerEndpoint::kPhaseChecks) {
      CHECK_THROWS_WITH(e.update(1000), Catch::Contains("ServerEndpoint::update"));
      CHECK_THROWS_WITH(e.timer_jobs(1000), Catch::Contains("timer_jobs"));
      CHECK_THROWS_WITH(e.settle_timers(1000), Catch::Contains("settle_timers"));
      CHECK_THROWS_WITH(e.seats_in_room(1), Catch::Contains("members_of"));  // fills its index
      CHECK_THROWS_WITH(e.take_datagrams(), Catch::Contains("take_datagrams"));
      CHECK_THROWS_WITH(e.set_server_tick(1, 5), Catch::Contains("set_server_tick"));
    }
    CHECK(e.inbox_datagrams() == 0);  // const reads stay allowed
    CHECK(e.sessions().empty());
  }
  CHECK_NOTHROW(e.update(1000));  // the phase is over
  CHECK(e.take_datagrams().empty());
}
