#include "fts/io/udp.hpp"

#include "fts/io/address.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <utility>

#ifdef __linux__
#include <sys/socket.h>
#include <unistd.h>
#endif

namespace fts::io {

std::string to_text(const udp::endpoint& ep) {
  return host_port_text(ep.address().to_string(), ep.port());
}

std::optional<udp::endpoint> endpoint_from_text(const std::string& text) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos) return std::nullopt;
  std::string_view host(text.data(), colon);
  if (!host.empty() && host.front() == '[') {
    if (host.size() < 2 || host.back() != ']') return std::nullopt;
    host = host.substr(1, host.size() - 2);
  }
  // A NUL-terminated copy on the stack: the server parses every datagram's address, and
  // an IPv6 one would not fit a string's inline buffer.
  std::array<char, 64> buffer{};
  if (host.size() >= buffer.size()) return std::nullopt;
  std::memcpy(buffer.data(), host.data(), host.size());
  boost::system::error_code ec;
  const auto address = asio::ip::make_address(buffer.data(), ec);
  if (ec) return std::nullopt;
  const unsigned long port = std::strtoul(text.c_str() + colon + 1, nullptr, 10);
  if (port > 65535) return std::nullopt;
  return udp::endpoint(address, static_cast<unsigned short>(port));
}

std::optional<udp::endpoint> resolve(asio::io_context& io, const std::string& host, const std::string& port,
                                     std::string& error) {
  boost::system::error_code ec;
  udp::resolver resolver(io);
  const auto results = resolver.resolve(host, port, ec);
  if (ec || results.empty()) {
    error = ec ? ec.message() : "no address";
    return std::nullopt;
  }
  return *results.begin();
}

boost::system::error_code UdpSocket::bind(const udp::endpoint& local) {
  close();
  boost::system::error_code ec;
  socket_.open(local.protocol(), ec);
  if (!ec) socket_.bind(local, ec);
  if (!ec) socket_.non_blocking(true, ec);
  if (!ec) {
    boost::system::error_code ignored;  // a smaller buffer than asked is no failure
    socket_.set_option(udp::socket::receive_buffer_size(kServerBufferBytes), ignored);
    socket_.set_option(udp::socket::send_buffer_size(kServerBufferBytes), ignored);
  }
  return ec;
}

std::size_t UdpSocket::receive_buffer_bytes() const {
#ifdef __linux__
  if (polled_ >= 0) {
    int size = 0;
    socklen_t len = sizeof(size);
    return ::getsockopt(polled_, SOL_SOCKET, SO_RCVBUF, &size, &len) == 0 ? static_cast<std::size_t>(size) : 0;
  }
#endif
  udp::socket::receive_buffer_size size;
  boost::system::error_code ec;
  socket_.get_option(size, ec);
  return ec ? 0 : static_cast<std::size_t>(size.value());
}

boost::system::error_code UdpSocket::connect(const udp::endpoint& server, const std::optional<asio::ip::address>& from) {
  close();
  boost::system::error_code ec;
  socket_.open(server.protocol(), ec);
  if (!ec && from) socket_.bind(udp::endpoint(*from, 0), ec);
  if (!ec) socket_.connect(server, ec);
  return ec;
}

void UdpSocket::start_receiving(Handler on_datagram, std::function<void()> on_burst_end, Wake wake) {
  on_datagram_ = std::move(on_datagram);
  on_burst_end_ = std::move(on_burst_end);
#ifdef __linux__
  // Out of the reactor: Asio registers a socket edge-triggered when it opens it, so even
  // with no read waiting every arrival would wake the loop. release() deregisters it and
  // hands over the descriptor (non-blocking; MSG_DONTWAIT is passed all the same).
  if (wake == Wake::when_asked) {
    if (polled_ < 0 && socket_.is_open()) {
      boost::system::error_code ec;
      polled_ = socket_.release(ec);
      if (ec) polled_ = -1;
    }
    if (polled_ >= 0) return;
  }
#else
  (void)wake;
#endif
  receive_next(generation_);
}

std::size_t UdpSocket::take_waiting() { return polled_ >= 0 ? drain(generation_, kRoundsPerTake) : 0; }

// One wake-up when the socket is readable; the datagrams are then taken without waiting.
void UdpSocket::receive_next(std::uint64_t generation) {
  socket_.async_wait(udp::socket::wait_read, [this, generation](const boost::system::error_code& ec) {
    if (ec == asio::error::operation_aborted || generation != generation_) return;
    if (!ec) {
      drain(generation, kRoundsPerWakeup);
      if (generation == generation_ && on_burst_end_) on_burst_end_();
    }
    if (generation == generation_ && socket_.is_open()) receive_next(generation);
  });
}

#ifdef __linux__
std::size_t UdpSocket::drain(std::uint64_t generation, std::size_t rounds) {
  std::size_t taken = 0;
  std::array<mmsghdr, kBatch> msgs{};
  std::array<iovec, kBatch> iov{};
  std::array<sockaddr_storage, kBatch> from{};
  for (std::size_t round = 0; round < rounds; ++round) {
    for (std::size_t i = 0; i < kBatch; ++i) {
      iov[i] = {buffers_[i].data(), buffers_[i].size()};
      msgs[i] = {};
      msgs[i].msg_hdr.msg_name = &from[i];
      msgs[i].msg_hdr.msg_namelen = sizeof(sockaddr_storage);
      msgs[i].msg_hdr.msg_iov = &iov[i];
      msgs[i].msg_hdr.msg_iovlen = 1;
    }
    const int n = ::recvmmsg(fd(), msgs.data(), kBatch, MSG_DONTWAIT, nullptr);
    if (n <= 0) break;  // nothing more now (EAGAIN), or an ICMP error: skipped
    ++receive_calls_;
    datagrams_received_ += static_cast<std::uint64_t>(n);
    taken += static_cast<std::size_t>(n);
    for (int i = 0; i < n; ++i) {
      udp::endpoint sender;
      const std::size_t len = std::min<std::size_t>(msgs[i].msg_hdr.msg_namelen, sender.capacity());
      std::memcpy(sender.data(), &from[i], len);
      sender.resize(len);
      const std::size_t bytes = std::min<std::size_t>(msgs[i].msg_len, buffers_[i].size());
      if (on_datagram_) on_datagram_(sender, std::span<const std::uint8_t>(buffers_[i].data(), bytes));
      if (generation != generation_) return taken;  // closed by the handler
    }
    if (static_cast<std::size_t>(n) < kBatch) break;
  }
  return taken;
}

std::size_t UdpSocket::send_batch(std::span<const Outgoing> batch) {
  std::array<mmsghdr, kBatch> msgs{};
  std::array<iovec, kBatch> iov{};
  std::size_t failed = 0;
  std::size_t done = 0;
  while (done < batch.size()) {
    const std::size_t n = std::min(kBatch, batch.size() - done);
    for (std::size_t i = 0; i < n; ++i) {
      const Outgoing& o = batch[done + i];
      iov[i] = {const_cast<std::uint8_t*>(o.bytes.data()), o.bytes.size()};
      msgs[i] = {};
      msgs[i].msg_hdr.msg_name = const_cast<sockaddr*>(o.to.data());
      msgs[i].msg_hdr.msg_namelen = static_cast<socklen_t>(o.to.size());
      msgs[i].msg_hdr.msg_iov = &iov[i];
      msgs[i].msg_hdr.msg_iovlen = 1;
    }
    const int sent = ::sendmmsg(fd(), msgs.data(), static_cast<unsigned>(n), MSG_DONTWAIT);
    // sendmmsg stops at the first datagram that fails: that one is counted and skipped.
    const std::size_t ok = sent > 0 ? static_cast<std::size_t>(sent) : 0;
    done += ok;
    if (ok < n) {
      ++failed;
      ++send_errors_;
      ++done;
    }
  }
  return failed;
}
#else
std::size_t UdpSocket::drain(std::uint64_t generation, std::size_t rounds) {
  std::size_t taken = 0;
  for (std::size_t i = 0; i < kBatch * rounds; ++i) {
    udp::endpoint sender;
    boost::system::error_code ec;
    const std::size_t n = socket_.receive_from(asio::buffer(buffers_[0]), sender, 0, ec);
    if (ec) break;
    ++receive_calls_;
    ++datagrams_received_;
    ++taken;
    if (on_datagram_) on_datagram_(sender, std::span<const std::uint8_t>(buffers_[0].data(), n));
    if (generation != generation_) return taken;
  }
  return taken;
}

std::size_t UdpSocket::send_batch(std::span<const Outgoing> batch) {
  std::size_t failed = 0;
  for (const auto& o : batch) failed += send(o.bytes, o.to) ? 0 : 1;
  return failed;
}
#endif

bool UdpSocket::send(std::span<const std::uint8_t> bytes, const std::optional<udp::endpoint>& to) {
  if (polled_ >= 0) {  // out of Asio's hands: the batch's system call
    if (!to) {  // a socket out of the reactor is a server's, and a server names the peer
      ++send_errors_;
      return false;
    }
    const Outgoing one{*to, bytes};
    return send_batch({&one, 1}) == 0;
  }
  boost::system::error_code ec;
  if (to) socket_.send_to(asio::buffer(bytes.data(), bytes.size()), *to, 0, ec);
  else socket_.send(asio::buffer(bytes.data(), bytes.size()), 0, ec);
  if (ec) ++send_errors_;
  return !ec;
}

void UdpSocket::close() {
  ++generation_;
  if (polled_ >= 0) ::close(std::exchange(polled_, -1));
  boost::system::error_code ec;
  if (socket_.is_open()) socket_.close(ec);
}

udp::endpoint UdpSocket::local_endpoint() const {
#ifdef __linux__
  if (polled_ >= 0) {
    udp::endpoint local;
    socklen_t len = static_cast<socklen_t>(local.capacity());
    if (::getsockname(polled_, local.data(), &len) != 0) return {};
    local.resize(len);
    return local;
  }
#endif
  boost::system::error_code ec;
  return socket_.local_endpoint(ec);
}

}  // namespace fts::io
