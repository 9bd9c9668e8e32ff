// Real protocol clients against a GameHost in memory, time stepped by hand: client i
// sends from 10.0.0.(i+1):5000, and tick() moves every datagram both ways around one
// host tick of 10 ms. Tests derive from it to set options before start() and to add
// their own steps.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "app/console_commands.hpp"
#include "app/game_host.hpp"
#include "fts/protocol/client.hpp"

namespace fts::test {

// A room's record directory (GameHost::record_to), removed at the end of the test.
struct RecordDir {
  std::filesystem::path path;
  explicit RecordDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() / ("fts-record-" + std::to_string(::getpid()) + "-" + name)) {
    std::filesystem::remove_all(path);
  }
  ~RecordDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

struct HostRig {
  server::Options options;
  sim::MatchConfig config;
  std::unique_ptr<server::GameHost> host;
  std::vector<std::unique_ptr<protocol::ClientEndpoint>> clients;
  std::uint64_t now = 1000;
  protocol::ServerKey key{};

  void start() { host = std::make_unique<server::GameHost>(options, config, key); }
  static std::string address(std::size_t i) { return "10.0.0." + std::to_string(i + 1) + ":5000"; }
  // When set, the next clients connect from this host (a household, an attacker), each
  // from its own port (5000 + its index); else client i is alone on host 10.0.0.(i+1).
  std::string next_host;
  // A client that starts its handshake now (it is welcomed over the next ticks).
  protocol::ClientEndpoint& connect(const protocol::ClientConfig& c) {
    const std::size_t i = clients.size();
    addresses.push_back(next_host.empty() ? address(i) : next_host + ":" + std::to_string(5000 + i));
    index_of[addresses.back()] = i;
    clients.push_back(std::make_unique<protocol::ClientEndpoint>(c));
    clients.back()->connect(now);
    return *clients.back();
  }
  protocol::ClientEndpoint& add(const std::string& name) {
    protocol::ClientConfig c;
    c.name = name;
    return connect(c);
  }
  // A client asking to join `how` ("create", "quick", "join" a room code...; a token to
  // come back), ticked until it is welcomed or refused (at most 50 ticks).
  protocol::ClientEndpoint& join(const std::string& name, const std::string& how, const std::string& room = "",
                                 const std::string& token = "") {
    protocol::ClientConfig c;
    c.name = name;
    c.join = how;
    c.room = room;
    c.token = token;
    auto& client = connect(c);
    for (int i = 0; i < 50 && client.state() == protocol::ClientState::connecting; ++i) tick();
    return client;
  }
  // Every client's datagrams to the host.
  void send() {
    for (std::size_t i = 0; i < clients.size(); ++i) {
      clients[i]->update(now);
      for (auto& d : clients[i]->take_datagrams()) host->receive(addresses[i], d, now);
    }
  }
  // When set, deliver() notes each datagram as "address size", in the order sent.
  std::vector<std::string>* sent_log = nullptr;
  // The host's datagrams to their clients.
  void deliver() {
    for (auto& out : host->take_datagrams()) {
      if (sent_log) sent_log->push_back(out.to + " " + std::to_string(out.bytes.size()));
      clients[index_of.at(out.to)]->receive(out.bytes, now);
    }
  }
  // A console request (JSON text, read as the console socket's line is) and its reply;
  // the datagrams it caused are delivered.
  nlohmann::ordered_json console(const std::string& text) {
    auto reply = server::console_line(*host, text, now);
    deliver();
    return reply;
  }
  std::vector<std::string> addresses;                     // client i's address
  std::unordered_map<std::string, std::size_t> index_of;  // address -> client
  void tick() {
    send();
    host->tick(now);
    deliver();
    now += 10;
  }
  // Ticks until every client is connected (at most `ticks`); whether they all are.
  bool connect_all(int ticks = 50) {
    const auto all = [&] {
      for (const auto& c : clients)
        if (c->state() != protocol::ClientState::connected) return false;
      return true;
    };
    for (int i = 0; i < ticks && !all(); ++i) tick();
    return all();
  }
};

}  // namespace fts::test
