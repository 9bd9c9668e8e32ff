// UdpSocket's two ways to learn of datagrams: a client's socket wakes its loop when one
// comes (Wake::on_arrival); a server's leaves the loop alone and is read when asked
// (Wake::when_asked, take_waiting), at its ticks. Real sockets on 127.0.0.1; loopback
// queues a datagram at the receiver before the sender's call returns, so nothing waits.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "fts/io/udp.hpp"

using fts::io::UdpSocket;
namespace asio = boost::asio;

namespace {

struct Pair {
  asio::io_context io;
  UdpSocket server{io}, client{io};
  std::vector<std::string> heard;
  int bursts = 0;

  explicit Pair(UdpSocket::Wake wake) {
    REQUIRE(!server.bind(fts::io::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0)));
    server.start_receiving(
        [this](const fts::io::udp::endpoint&, std::span<const std::uint8_t> bytes) {
          heard.emplace_back(bytes.begin(), bytes.end());
        },
        [this] { ++bursts; }, wake);
    REQUIRE(!client.connect(server.local_endpoint()));
  }
  void send(const std::string& text) {
    REQUIRE(client.send(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())));
  }
};

}  // namespace

TEST_CASE("UdpSocket: a socket read when asked never wakes the loop, and takes all that waits",
          "[net][udp]") {
  Pair p(UdpSocket::Wake::when_asked);
  CHECK(p.server.local_endpoint().port() != 0);  // still known out of the reactor
  CHECK(p.server.receive_buffer_bytes() > 0);
  p.send("one");
  p.send("two");
  p.send("three");
  CHECK(p.io.poll() == 0);  // no handler ran: the datagrams woke nothing
  CHECK(p.heard.empty());
  CHECK(p.server.take_waiting() == 3);
  CHECK(p.heard == std::vector<std::string>{"one", "two", "three"});
  CHECK(p.bursts == 0);  // the owner sends when it is done
  CHECK(p.server.take_waiting() == 0);  // nothing left, and no waiting for more

  // More than one system call's batch comes out in one take, in order.
  for (std::size_t i = 0; i < UdpSocket::kBatch + 5; ++i) p.send(std::to_string(i));
  CHECK(p.server.take_waiting() == UdpSocket::kBatch + 5);
  CHECK(p.heard.back() == std::to_string(UdpSocket::kBatch + 4));

  // It answers through the batch's call, and its descriptor closes with it.
  const std::string reply = "back";
  CHECK(p.server.send(std::span(reinterpret_cast<const std::uint8_t*>(reply.data()), reply.size()),
                      p.client.local_endpoint()));
  p.server.close();
  CHECK(p.server.take_waiting() == 0);
}

TEST_CASE("UdpSocket: a socket read on arrival hands each burst to its loop", "[net][udp]") {
  Pair p(UdpSocket::Wake::on_arrival);
  p.send("one");
  p.send("two");
  CHECK(p.server.take_waiting() == 0);  // not this socket's way
  for (int i = 0; i < 10 && p.heard.size() < 2; ++i) p.io.poll_one();
  CHECK(p.heard == std::vector<std::string>{"one", "two"});
  CHECK(p.bursts >= 1);
}
