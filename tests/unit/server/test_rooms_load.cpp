// The host's own cost with 32 rooms x 8 clients (issue 13), in memory: real protocol
// clients, time stepped by hand, only the host's calls (receive, tick, take_datagrams)
// timed. Reports figures (never passes or fails on time); hidden, run by the soak label:
//   build/tests/fts_server_tests "[rooms-load]"
// FTS_LOAD_ROOMS=64 measures 64 rooms (512 clients). The clients send their input the
// lean way (hold_input), as fts-bot and fts-client do.
#include <catch2/catch.hpp>

#include <time.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "app/game_host.hpp"
#include "fts/protocol/client.hpp"
#include "../../support/load_player.hpp"

using namespace fts;

TEST_CASE("Rooms load: 32 rooms x 8 players, host time per tick", "[.][soak][rooms-load]") {
  const char* rooms_env = std::getenv("FTS_LOAD_ROOMS");
  const int kRooms = rooms_env ? std::clamp(std::atoi(rooms_env), 1, 256) : 32;
  constexpr int kSeats = 8, kTicks = 1000;
  server::Options options;
  options.max_players = kSeats;
  options.max_rooms = kRooms;
  options.max_per_address = 4;
  sim::MatchConfig config;
  server::GameHost host(options, config, protocol::ServerKey{});
  std::vector<std::unique_ptr<protocol::ClientEndpoint>> clients;
  std::vector<std::string> addresses;
  std::uint64_t now = 1000;
  for (int i = 0; i < kRooms * kSeats; ++i) {
    protocol::ClientConfig c;
    c.name = "p" + std::to_string(i);
    clients.push_back(std::make_unique<protocol::ClientEndpoint>(c));
    addresses.push_back("10." + std::to_string(i / 250) + "." + std::to_string(i % 250) + ".1:5000");
  }
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < addresses.size(); ++i) index[addresses[i]] = i;
  std::vector<double> tick_us;
  double receive_us = 0;  // of which in receive()
  // Thread CPU time, not wall time: the machine is shared, and being descheduled is not
  // the host's cost.
  auto cpu_us = [] {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) / 1e3;
  };
  auto step = [&](bool timed, bool play) {
    double us = 0;
    for (std::size_t i = 0; i < clients.size(); ++i) {
      auto& c = *clients[i];
      if (play) test::play_load_tick(c, i, now);
      c.update(now);
      auto datagrams = c.take_datagrams();
      const double t0 = cpu_us();
      for (auto& d : datagrams) host.receive(addresses[i], d, now);
      us += cpu_us() - t0;
      if (timed) receive_us += cpu_us() - t0;
    }
    const double t0 = cpu_us();
    host.tick(now);
    auto out = host.take_datagrams();
    us += cpu_us() - t0;
    for (auto& d : out) clients[index.at(d.to)]->receive(d.bytes, now);
    if (timed) tick_us.push_back(us);
    now += 10;
  };
  // Everyone connects (a few at a time, as over a network), then the matches run.
  for (std::size_t i = 0; i < clients.size(); ++i) {
    clients[i]->connect(now);
    if (i % 8 == 7) step(false, false);
  }
  for (int i = 0; i < 100; ++i) step(false, true);
  REQUIRE(host.room_ids().size() == static_cast<std::size_t>(kRooms));
  for (auto id : host.room_ids()) CHECK(host.endpoint().seats_in_room(id) == kSeats);
  for (int i = 0; i < kTicks; ++i) step(true, true);
  int playing = 0;
  for (auto id : host.room_ids()) playing += host.room(id)->match().phase == sim::Phase::playing;
  CHECK(playing > 0);
  std::sort(tick_us.begin(), tick_us.end());
  const double p50 = tick_us[tick_us.size() / 2], p99 = tick_us[tick_us.size() * 99 / 100], max = tick_us.back();
  double sum = 0;
  for (double v : tick_us) sum += v;
  std::cout << "rooms-load: " << kRooms << " rooms x " << kSeats << " players, " << kTicks << " ticks; rooms playing "
            << playing << "; host CPU per tick (receive + tick + take) p50 " << p50 << " us, p99 " << p99
            << " us, max " << max << " us, mean " << sum / kTicks << " us = " << sum / kTicks / 10000 * 100
            << "% of a core at 100 Hz (receive " << receive_us / kTicks << " us), " << sum / kTicks * 100 / (kRooms * kSeats) << " us CPU per client per second\n";
}
