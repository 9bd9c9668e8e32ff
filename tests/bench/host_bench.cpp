// fts-host-bench: the host's cost per client in memory (issue 29's capacity model).
// Real protocol clients (protocol::ClientEndpoint, one per address, playing on the lean
// uplink as fts-bot does) against a GameHost with --threads T, time stepped by hand:
// per tick, the clients' datagrams are gathered first, then only the host's calls
// (receive of every datagram, tick, take_datagrams) are timed: wall time (what the 10 ms
// budget at 100 Hz is about) and process CPU time (every pool thread's, the clients do
// not run meanwhile). Memory is the socket run's (server_load.py: the server's RSS), as
// the clients here share the host's heap. Prints a table and, with --csv, writes it.
// Reports figures, never judges.
//
// --phase in: every client's clock is the host's, so all their frames and keep-alives fall
// on the same ticks (the worst case). --phase out: client i's clock runs 10 * (97 i mod
// 120) ms ahead (up to 1.19 s, a whole number of ticks), as real clients that connected
// at different moments: their frames spread over the ticks.
//
//   build/tests/bench/fts-host-bench --clients 8,64,512,1024 --threads 1,2 --ticks 1000
//   build/tests/bench/fts-host-bench --clients 512,1024,2048 --threads 1,2 --phase in,out
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/game_host.hpp"
#include "fts/protocol/client.hpp"
#include "../support/load_player.hpp"

using namespace fts;

namespace {

double cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) / 1e3;
}
double wall_us() {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Row {
  std::string phase;
  int clients = 0, rooms = 0, threads = 0, ticks = 0;
  double wall_p50 = 0, wall_p99 = 0, wall_max = 0, wall_mean = 0, cpu_mean = 0;
  double bytes_in = 0, bytes_out = 0;  // per client per second
  int playing = 0;
};

Row measure(int clients_n, int seats, unsigned threads, int ticks, bool out_of_phase) {
  server::Options options;
  options.max_players = static_cast<std::uint32_t>(seats);
  options.max_rooms = static_cast<std::uint32_t>((clients_n + seats - 1) / seats);
  options.threads = threads;
  sim::MatchConfig config;
  server::GameHost host(options, config, protocol::ServerKey{});
  std::vector<std::unique_ptr<protocol::ClientEndpoint>> clients;
  std::vector<std::string> addresses;
  std::map<std::string, std::size_t> index;
  std::vector<std::uint64_t> ahead;  // each client's clock minus the host's (ms)
  for (int i = 0; i < clients_n; ++i) {
    ahead.push_back(out_of_phase ? 10 * static_cast<std::uint64_t>((i * 97) % 120) : 0);
    protocol::ClientConfig c;
    c.name = "p" + std::to_string(i);
    clients.push_back(std::make_unique<protocol::ClientEndpoint>(c));
    addresses.push_back("10." + std::to_string(i / 250) + "." + std::to_string(i % 250) + ".1:5000");
    index[addresses.back()] = static_cast<std::size_t>(i);
  }
  std::uint64_t now = 1000;
  std::vector<std::pair<std::size_t, std::vector<std::uint8_t>>> inbox;
  std::vector<protocol::Outgoing> batch;
  std::vector<double> wall;
  double cpu_sum = 0, bytes_in = 0, bytes_out = 0;
  auto step = [&](bool timed, bool play) {
    inbox.clear();
    for (std::size_t i = 0; i < clients.size(); ++i) {
      auto& c = *clients[i];
      const std::uint64_t own = now + ahead[i];
      if (play) test::play_load_tick(c, i, own);
      c.update(own);
      for (auto& d : c.take_datagrams()) inbox.emplace_back(i, std::move(d));
    }
    const double w0 = wall_us(), c0 = cpu_us();
    for (const auto& [i, d] : inbox) host.receive(addresses[i], d, now);
    host.tick(now);
    host.take_datagrams(batch);
    const double w1 = wall_us(), c1 = cpu_us();
    if (timed) {
      wall.push_back(w1 - w0);
      cpu_sum += c1 - c0;
      for (const auto& [i, d] : inbox) bytes_in += static_cast<double>(d.size());
      for (const auto& d : batch) bytes_out += static_cast<double>(d.bytes.size());
    }
    for (const auto& d : batch) {
      const std::size_t i = index.at(d.to);
      clients[i]->receive(d.bytes, now + ahead[i]);
    }
    now += 10;
  };
  for (std::size_t i = 0; i < clients.size(); ++i) {
    clients[i]->connect(now + ahead[i]);
    if (i % 8 == 7) step(false, false);
  }
  for (int i = 0; i < 100; ++i) step(false, true);
  for (int i = 0; i < ticks; ++i) step(true, true);
  Row r;
  r.phase = out_of_phase ? "out" : "in";
  r.clients = clients_n;
  r.rooms = static_cast<int>(host.room_ids().size());
  r.threads = static_cast<int>(host.workers().threads());
  r.ticks = ticks;
  for (auto id : host.room_ids()) r.playing += host.room(id)->match().phase == sim::Phase::playing;
  std::sort(wall.begin(), wall.end());
  r.wall_p50 = wall[wall.size() / 2];
  r.wall_p99 = wall[wall.size() * 99 / 100];
  r.wall_max = wall.back();
  for (double v : wall) r.wall_mean += v / static_cast<double>(wall.size());
  r.cpu_mean = cpu_sum / ticks;
  const double seconds = ticks / 100.0;
  r.bytes_in = bytes_in / clients_n / seconds;
  r.bytes_out = bytes_out / clients_n / seconds;
  return r;
}

std::vector<std::string> words(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

std::vector<int> ints(const std::string& list) {
  std::vector<int> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stoi(item));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fts-host-bench: the host's CPU, heap and bytes per client, in memory"};
  std::string clients_list = "8,64,512,1024", threads_list = "1,2", phase_list = "in", csv;
  int ticks = 1000, seats = 8;
  app.add_option("--clients", clients_list, "client counts, comma-separated");
  app.add_option("--threads", threads_list, "thread counts, comma-separated");
  app.add_option("--ticks", ticks, "timed ticks per cell (100 Hz)")->check(CLI::Range(10, 100000));
  app.add_option("--seats", seats, "players per room")->check(CLI::Range(1, 64));
  app.add_option("--phase", phase_list, "in (clients' frames on the same ticks), out (spread), or in,out");
  app.add_option("--csv", csv, "also write the table here");
  CLI11_PARSE(app, argc, argv);
  for (const auto& p : words(phase_list))
    if (p != "in" && p != "out") {
      std::cerr << "fts-host-bench: --phase takes in, out or in,out, not " << p << "\n";
      return 2;
    }
  const std::string header =
      "phase,clients,rooms,threads,rooms_playing,wall_p50_us,wall_p99_us,wall_max_us,wall_mean_us,cpu_mean_us,"
      "core_pct_at_100hz,cpu_us_per_client_s,bytes_in_client_s,bytes_out_client_s";
  std::ostringstream table;
  table << header << "\n";
  std::cout << header << std::endl;
  for (const auto& phase : words(phase_list))
    for (int n : ints(clients_list))
      for (int t : ints(threads_list)) {
        const Row r = measure(n, seats, static_cast<unsigned>(t), ticks, phase == "out");
        char line[512];
        std::snprintf(line, sizeof line, "%s,%d,%d,%d,%d,%.0f,%.0f,%.0f,%.0f,%.0f,%.2f,%.1f,%.0f,%.0f",
                      r.phase.c_str(), r.clients, r.rooms, r.threads, r.playing, r.wall_p50, r.wall_p99, r.wall_max,
                      r.wall_mean, r.cpu_mean, r.cpu_mean / 10000 * 100, r.cpu_mean * 100 / r.clients, r.bytes_in,
                      r.bytes_out);
        table << line << "\n";
        std::cout << line << std::endl;
      }
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << table.str();
    if (!out) {
      std::cerr << "fts-host-bench: cannot write " << csv << "\n";
      return 1;
    }
  }
  return 0;
}
