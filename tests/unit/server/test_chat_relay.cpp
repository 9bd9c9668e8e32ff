#include <catch2/catch.hpp>

#include "app/chat_relay.hpp"

using fts::server::ChatLimits;
using fts::server::ChatRelay;

TEST_CASE("chat lines are cleaned: printable ASCII, spaces collapsed, cut to length", "[server][chat]") {
  CHECK(ChatRelay::clean("  hello \t  there  ", 120) == "hello there");
  CHECK(ChatRelay::clean("red\x1b[31mtext\x07", 120) == "red[31mtext");  // no escape byte survives
  CHECK(ChatRelay::clean("caf\xc3\xa9!", 120) == "caf?!");
  CHECK(ChatRelay::clean(std::string(300, 'x'), 120).size() == 120);
  CHECK(ChatRelay::clean("\x01\x02 \x7f", 120).empty());
}

TEST_CASE("chat is rate-limited per player with a token bucket", "[server][chat]") {
  ChatLimits limits;
  limits.burst_lines = 3;
  limits.refill_ms = 1000;
  ChatRelay relay(limits);
  const std::uint64_t t = 10'000;
  for (int i = 0; i < 3; ++i) CHECK(relay.accept(1, "hi", t).ok);
  const auto refused = relay.accept(1, "hi", t);
  CHECK_FALSE(refused.ok);
  CHECK(refused.code == fts::protocol::ResultCode::rate);
  CHECK(relay.accept(2, "me too", t).ok);  // another player has its own bucket
  CHECK_FALSE(relay.accept(1, "hi", t + 999).ok);
  CHECK(relay.accept(1, "hi", t + 1000).ok);  // one line back per refill_ms
  const auto empty = relay.accept(3, " \x1b ", t);
  CHECK_FALSE(empty.ok);
  CHECK(empty.code == fts::protocol::ResultCode::empty);
  CHECK(relay.accept(3, "  a  b ", t).text == "a b");
}
