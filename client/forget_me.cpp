// The connection of fts-client --forget-me; an Asio translation unit of fts-client with
// main_client.cpp and game.cpp.
#include "forget_me.hpp"

#include <chrono>
#include <iostream>

#include "fts/protocol/client.hpp"
#include "net/clock.hpp"
#include "ui/forget.hpp"
#include "ui/sanitize.hpp"

namespace fts::client {
namespace proto = fts::protocol;

namespace {

constexpr std::uint64_t kAnswerMs = 15000;

}  // namespace

int forget_me(fts::io::asio::io_context& io, const Options& opts, const fts::io::udp::endpoint& server,
              const std::string& identity_path) {
  const std::string where = opts.host + ":" + opts.port;
  if (!opts.identity) {
    std::cerr << "fts-client: --forget-me needs your identity\n";
    return 1;
  }
  if (!opts.yes) {
    std::cout << forget_prompt(where, proto::fingerprint(*opts.identity), identity_path) << std::flush;
    std::string line;
    if (!std::getline(std::cin, line) || !forget_confirmed(line)) {
      std::cout << "\nNothing was erased.\n";
      return 1;
    }
  }
  proto::ClientEndpoint ep(connection_config(opts, std::nullopt));
  fts::io::UdpSocket socket(io);
  if (const auto ec = socket.connect(server)) {
    std::cerr << "fts-client: cannot open a socket: " << ec.message() << "\n";
    return 1;
  }
  socket.start_receiving([&](const fts::io::udp::endpoint&, std::span<const std::uint8_t> bytes) {
    ep.receive(bytes, now_ms());
  });
  const auto flush = [&] {
    for (auto& d : ep.take_datagrams()) socket.send(d);
  };
  const std::uint64_t start = now_ms();
  ep.connect(start);
  std::uint32_t rid = 0;
  int code = 1;
  std::string said;
  bool answered = false;
  while (!answered && now_ms() - start < kAnswerMs) {
    const std::uint64_t now = now_ms();
    ep.update(now);
    if (ep.state() == proto::ClientState::connected && rid == 0) rid = ep.send_command(proto::CommandOp::forget, 0, now);
    for (const auto& r : ep.take_results()) {
      if (rid == 0 || r.command_rid != rid) continue;
      const ForgetOutcome o = forget_outcome(r, identity_path);
      code = o.erased ? 0 : 1;
      said = o.text;
      answered = true;
    }
    if (!answered && (ep.state() == proto::ClientState::refused || ep.state() == proto::ClientState::timed_out ||
                      ep.state() == proto::ClientState::disconnected)) {
      said = "not erased: " +
             (ep.error() ? "the server said: " + sanitize(ep.error()->message, 200) : std::string("no answer"));
      answered = true;
    }
    flush();
    io.run_for(std::chrono::milliseconds(20));
    if (io.stopped()) io.restart();
  }
  if (ep.state() == proto::ClientState::connected) {
    ep.disconnect(now_ms(), proto::kProbeByeReason);  // a probe's bye: the server keeps no player of it
    flush();
  }
  socket.close();
  if (!answered) said = "not erased: no answer from the server at " + where;
  (code == 0 ? std::cout : std::cerr) << (code == 0 ? "" : "fts-client: ") << said << "\n";
  return code;
}

}  // namespace fts::client
