#include "fts/io/udp.hpp"

#include <cstdlib>

namespace fts::io {

std::string to_text(const udp::endpoint& ep) {
  const auto a = ep.address();
  return (a.is_v6() ? "[" + a.to_string() + "]" : a.to_string()) + ":" + std::to_string(ep.port());
}

std::optional<udp::endpoint> endpoint_from_text(const std::string& text) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos) return std::nullopt;
  std::string host = text.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[') host = host.substr(1, host.size() - 2);
  boost::system::error_code ec;
  const auto address = asio::ip::make_address(host, ec);
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
  return ec;
}

boost::system::error_code UdpSocket::connect(const udp::endpoint& server) {
  close();
  boost::system::error_code ec;
  socket_.open(server.protocol(), ec);
  if (!ec) socket_.connect(server, ec);
  return ec;
}

void UdpSocket::start_receiving(Handler on_datagram) {
  on_datagram_ = std::move(on_datagram);
  receive_next(generation_);
}

void UdpSocket::receive_next(std::uint64_t generation) {
  socket_.async_receive_from(asio::buffer(buffer_), sender_,
                             [this, generation](const boost::system::error_code& ec, std::size_t n) {
                               if (ec == asio::error::operation_aborted || generation != generation_) return;
                               if (!ec && on_datagram_)
                                 on_datagram_(sender_, std::span<const std::uint8_t>(buffer_.data(), n));
                               if (generation == generation_ && socket_.is_open()) receive_next(generation);
                             });
}

bool UdpSocket::send(std::span<const std::uint8_t> bytes, const std::optional<udp::endpoint>& to) {
  boost::system::error_code ec;
  if (to) socket_.send_to(asio::buffer(bytes.data(), bytes.size()), *to, 0, ec);
  else socket_.send(asio::buffer(bytes.data(), bytes.size()), 0, ec);
  if (ec) ++send_errors_;
  return !ec;
}

void UdpSocket::close() {
  ++generation_;
  boost::system::error_code ec;
  if (socket_.is_open()) socket_.close(ec);
}

udp::endpoint UdpSocket::local_endpoint() const {
  boost::system::error_code ec;
  return socket_.local_endpoint(ec);
}

}  // namespace fts::io
