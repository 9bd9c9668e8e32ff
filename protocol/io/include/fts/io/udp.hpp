// The one UDP socket of the edges (fts-server, fts-client, fts-bot): open, bind or
// connect, a receive loop that hands every datagram to a callback, and sends whose
// failures are counted, not thrown (a lost datagram is the protocol's business).
// Batched on Linux: one read takes up to kBatch datagrams per recvmmsg call, and
// send_batch hands many datagrams to one sendmmsg call. A socket is read either when it
// wakes its loop (Wake::on_arrival: clients, which answer at once) or when its owner asks
// (Wake::when_asked: the server, which reads at each tick; see take_waiting).
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
  // Calls per take_waiting() at most: 4096 datagrams, ten 100 Hz ticks of 2048 clients.
  // What a flood leaves beyond waits in the kernel's buffer for the next take, and what
  // overflows that buffer the kernel drops (as it would any datagram it cannot queue).
  static constexpr std::size_t kRoundsPerTake = 128;
  enum class Wake {
    on_arrival,  // the socket wakes the io_context's loop when datagrams come; they are read then
    when_asked,  // the socket never wakes the loop (it leaves the reactor): take_waiting() reads
  };
  struct Outgoing {
    udp::endpoint to;
    std::span<const std::uint8_t> bytes;
  };

  explicit UdpSocket(asio::io_context& io) : socket_(io) {}
  ~UdpSocket() { close(); }  // the descriptor taken from the reactor is this object's to close
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
  // answers in one batch). With Wake::when_asked (Linux; elsewhere the socket wakes the
  // loop as on_arrival) nothing is read until take_waiting(): a loop that wakes anyway at
  // fixed times (a server's ticks) reads in one go what came since, instead of waking for
  // every datagram (on a 2-core VM a wake-up costs about 10 µs of the process's CPU in
  // the context switch alone: BENCHMARKS.md, issue 39).
  void start_receiving(Handler on_datagram, std::function<void()> on_burst_end = {}, Wake wake = Wake::on_arrival);
  // Wake::when_asked: hands every datagram waiting now to `on_datagram` (at most
  // kRoundsPerTake calls; no waiting) and returns how many; on_burst_end is not called
  // (the owner sends when it is done). 0 in the other mode.
  std::size_t take_waiting();
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
  // Reads up to `rounds` batches; how many datagrams it handed on.
  std::size_t drain(std::uint64_t generation, std::size_t rounds);
  // The descriptor the system calls use: the socket's, or the one taken from the reactor.
  int fd() { return polled_ >= 0 ? polled_ : socket_.native_handle(); }

  udp::socket socket_;
  int polled_ = -1;  // Wake::when_asked: the descriptor, out of the io_context's reactor; owned
  std::array<std::array<std::uint8_t, 2048>, kBatch> buffers_{};
  Handler on_datagram_;
  std::function<void()> on_burst_end_;
  std::uint64_t receive_calls_ = 0;
  std::uint64_t datagrams_received_ = 0;
  std::uint64_t generation_ = 0;  // a callback of a closed socket's read ends there
  std::uint64_t send_errors_ = 0;
};

}  // namespace fts::io
