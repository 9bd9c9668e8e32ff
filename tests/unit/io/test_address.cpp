// HOST:PORT on the command lines of fts-client and fts-bot, and bind addresses.
#include <catch2/catch.hpp>

#include <string>

#include "fts/io/address.hpp"
#include "fts/io/udp.hpp"

using fts::io::parse_host_port;

TEST_CASE("Address: HOST:PORT splits at the last colon", "[net][address]") {
  auto hp = parse_host_port("127.0.0.1:7777");
  REQUIRE(hp);
  CHECK(hp->host == "127.0.0.1");
  CHECK(hp->port == "7777");
  hp = parse_host_port("[::1]:9000");
  REQUIRE(hp);
  CHECK(hp->host == "::1");
  CHECK(hp->port == "9000");
  hp = parse_host_port("server:http");
  REQUIRE(hp);
  CHECK(hp->port == "http");
  for (const char* bad : {"", "x", ":7777", "host:", "7777"}) {
    INFO(bad);
    CHECK_FALSE(parse_host_port(bad));
  }
}

TEST_CASE("Address: a bind address is a numeric IPv4 or IPv6 address", "[net][address]") {
  CHECK(fts::io::is_ip_address("0.0.0.0"));
  CHECK(fts::io::is_ip_address("::1"));
  CHECK_FALSE(fts::io::is_ip_address("localhost"));
  CHECK_FALSE(fts::io::is_ip_address("300.1.1.1"));
}

TEST_CASE("Address: the text a server queues a datagram to is read back to an endpoint", "[net][address]") {
  using fts::io::endpoint_from_text;
  using fts::io::to_text;
  for (const char* text : {"127.0.0.1:7777", "203.0.113.45:51234", "[::1]:9000",
                           "[2001:db8:85a3::8a2e:370:7334]:65535"}) {
    INFO(text);
    const auto e = endpoint_from_text(text);
    REQUIRE(e);
    CHECK(to_text(*e) == text);
  }
  const std::string too_long = "[" + std::string(70, '1') + "]:5";
  for (const std::string& bad : {std::string("127.0.0.1"), std::string("localhost:80"), std::string("1.2.3.4:70000"),
                                 std::string("[::1:5"), too_long}) {
    INFO(bad);
    CHECK_FALSE(endpoint_from_text(bad));
  }
}
