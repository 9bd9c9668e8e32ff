#include "fts/io/client_socket.hpp"

#include "fts/io/address.hpp"

namespace fts::io {

ClientSocket::Followed ClientSocket::follow(std::uint64_t attempt, std::uint64_t moves, const std::string& moved_to,
                                            UdpSocket::Handler on_datagram) {
  Followed f;
  if (open_ && attempt == attempt_) return f;
  attempt_ = attempt;
  if (moves < moves_) moves_ = moves;  // a new connection counts again; the room stays where it went
  if (moves != moves_) {
    moves_ = moves;
    std::string why;
    const auto to = parse_host_port(moved_to);
    if (const auto there = to ? resolve(io_, to->host, to->port, why) : std::nullopt) {
      server_ = *there;
      f.moved = true;
    } else {
      f.error = "the room moved to " + moved_to + ", which does not resolve" + (why.empty() ? "" : ": " + why);
    }
  }
  if (const auto ec = socket_.connect(server_, from_)) {
    f.error = "cannot open a socket: " + ec.message();
    return f;
  }
  socket_.start_receiving(std::move(on_datagram));
  open_ = f.opened = true;
  return f;
}

}  // namespace fts::io
