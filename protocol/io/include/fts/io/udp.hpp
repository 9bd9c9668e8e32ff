// The one UDP socket of the edges (fts-server, fts-client, fts-bot): open, bind or
// connect, a receive loop that hands every datagram to a callback, and sends whose
// failures are counted, not thrown (a lost datagram is the protocol's business).
// Batched on Linux: one wake-up drains up to kBatch datagrams per recvmmsg call, and
// send_batch hands many datagrams to one sendmmsg call.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "fts/io/asio.hpp"

namespace fts::io {

namespace asio = boost::asio;
using udp = asio::ip::udp;

// "1.2.3.4:5" or "[::1]:5": how the sans-I/O layers name a peer.
std::string to_text(const udp::endpoint& endpoint);
// The reverse; nothing for text that is not a numeric address and port.
std::optional<udp::endpoint> endpoint_from_text(const std::string& text);
// The first address HOST:PORT resolves to; nothing (and `error` set) when none.
std::optional<udp::endpoint> resolve(asio::io_context& io, const std::string& host, const std::string& port,
                                     std::string& error);

class UdpSocket {
 public:
  using Handler = std::function<void(const udp::endpoint& from, std::span<const std::uint8_t> bytes)>;
  // Datagrams taken per system call, and calls per wake-up at most (then other work,
  // such as a due tick, gets its turn before the next wake-up drains more).
  static constexpr std::size_t kBatch = 32;
  static constexpr std::size_t kRoundsPerWakeup = 4;
  struct Outgoing {
    udp::endpoint to;
    std::span<const std::uint8_t> bytes;
  };

  explicit UdpSocket(asio::io_context& io) : socket_(io) {}
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  // A server's socket on a local address (port 0: any free port), with receive and send
  // buffers of kServerBufferBytes asked for: the default 208 KiB overflowed when 512
  // clients of rooms handed over came at once (their hellos are padded to 1200 bytes),
  // and each lost hello cost its client a 250 ms resend. The kernel caps the ask at
  // net.core.rmem_max / wmem_max; receive_buffer_bytes() says what it gave.
  static constexpr int kServerBufferBytes = 4 << 20;
  boost::system::error_code bind(const udp::endpoint& local);
  std::size_t receive_buffer_bytes() const;
  // A client's socket: a fresh local port that hears only `server`. Calling it again
  // closes the old socket first (a reconnect from a new address).
  // `from`: send from this local address (any port) instead of the route's own.
  boost::system::error_code connect(const udp::endpoint& server,
                                    const std::optional<asio::ip::address>& from = std::nullopt);
  // Hands every datagram received from now on to `on_datagram`, until close() or the
  // next bind/connect; receive errors (an ICMP "port unreachable") are skipped.
  // `on_burst_end` runs once after every wake-up's datagrams (where a server sends its
  // answers in one batch).
  void start_receiving(Handler on_datagram, std::function<void()> on_burst_end = {});
  // Sends one datagram (to the connected peer when `to` is not given); false on error.
  bool send(std::span<const std::uint8_t> bytes, const std::optional<udp::endpoint>& to = std::nullopt);
  // Sends every datagram of `batch` (sendmmsg: one system call per kBatch); returns how
  // many failed (each also counted in send_errors).
  std::size_t send_batch(std::span<const Outgoing> batch);
  void close();

  udp::endpoint local_endpoint() const;
  std::uint64_t send_errors() const { return send_errors_; }
  // System calls that received at least one datagram, and the datagrams they carried.
  std::uint64_t receive_calls() const { return receive_calls_; }
  std::uint64_t datagrams_received() const { return datagrams_received_; }

 private:
  void receive_next(std::uint64_t generation);
  void drain(std::uint64_t generation);

  udp::socket socket_;
  std::array<std::array<std::uint8_t, 2048>, kBatch> buffers_{};
  Handler on_datagram_;
  std::function<void()> on_burst_end_;
  std::uint64_t receive_calls_ = 0;
  std::uint64_t datagrams_received_ = 0;
  std::uint64_t generation_ = 0;  // a callback of a closed socket's read ends there
  std::uint64_t send_errors_ = 0;
};

}  // namespace fts::io
