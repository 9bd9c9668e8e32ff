// A client's UDP socket to its server across connection attempts (fts-client, fts-bot):
// each attempt sends from a fresh local port (to the server a reconnect is a new address
// carrying the token; the old address would get the old session's answers), and the
// server's address follows a room that moved to another server (PROTOCOL.md 4.9b).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "fts/io/udp.hpp"

namespace fts::io {

class ClientSocket {
 public:
  // from: the local address to send from (fts-bot --source); none: the route's own.
  ClientSocket(asio::io_context& io, udp::endpoint server, std::optional<asio::ip::address> from = std::nullopt)
      : io_(io), socket_(io), server_(server), from_(from) {}

  struct Followed {
    bool opened = false;  // a fresh socket for a new attempt
    bool moved = false;   // to the room's new server
    std::string error;    // the move's address does not resolve (the old one stays), or no socket
  };
  // A connection's state now: its attempt, its moves and where the last one went. A new
  // attempt opens a fresh socket (to moved_to when moves is new and it resolves), whose
  // datagrams go to on_datagram.
  Followed follow(std::uint64_t attempt, std::uint64_t moves, const std::string& moved_to,
                  UdpSocket::Handler on_datagram);
  // The next follow() opens a fresh socket whatever the attempt (a new connection).
  void restart() { open_ = false; }
  void send(std::span<const std::uint8_t> bytes) { socket_.send(bytes); }
  void close() { socket_.close(); }
  const udp::endpoint& server() const { return server_; }

 private:
  asio::io_context& io_;
  UdpSocket socket_;
  udp::endpoint server_;
  std::optional<asio::ip::address> from_;
  std::uint64_t attempt_ = 0, moves_ = 0;
  bool open_ = false;
};

}  // namespace fts::io
