// Round trips of every message in both encodings, and golden bytes for a few.
#include <catch2/catch.hpp>

#include <algorithm>

#include "fts/protocol/codec.hpp"
#include "samples.hpp"

using namespace fts::protocol;

TEST_CASE("every message round-trips in both encodings", "[protocol][messages]") {
  for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
    for (const Message& m : test::all_messages()) {
      CAPTURE(static_cast<int>(enc), message_type(m));
      Header h;
      h.encoding = enc;
      h.session = 0xDEADBEEF;
      h.sequence = 65535;
      h.ack = 7;
      h.ack_bits = 0x80000001u;
      const auto bytes = encode_datagram(h, {m});
      REQUIRE(bytes.size() <= kMaxDatagramBytes);
      auto d = decode_datagram(bytes);
      REQUIRE(d.ok());
      CHECK(d->header == h);
      REQUIRE(d->messages.size() == 1);
      CHECK(d->messages[0] == m);
    }
  }
}

TEST_CASE("several messages share one datagram", "[protocol][messages]") {
  auto all = test::all_messages();
  all.resize(all.size() - 2);  // both snapshots together would pass 1200 bytes in JSON
  // A quarter of the control messages per datagram: a third of them (with chat, the
  // boards and `moved`) pass 1200 bytes in JSON, as half of them do (a welcome carrying a
  // tuned match's physics).
  const auto quarter = static_cast<std::ptrdiff_t>((all.size() + 3) / 4);
  std::vector<std::vector<Message>> parts;
  for (auto at = all.begin(); at != all.end(); at += std::min(quarter, all.end() - at))
    parts.emplace_back(at, at + std::min(quarter, all.end() - at));
  REQUIRE(parts.size() == 4);
  for (const auto& part : parts) {
    for (Encoding enc : {Encoding::json, Encoding::msgpack}) {
      Header h;
      h.encoding = enc;
      const auto bytes = encode_datagram(h, part);
      auto d = decode_datagram(bytes);
      INFO(bytes.size() << " bytes, " << part.size() << " messages");
      REQUIRE(d.ok());
      CHECK(d->messages == part);
    }
  }
}

TEST_CASE("golden bytes", "[protocol][messages][golden]") {
  Header h;
  h.encoding = Encoding::json;
  h.session = 0x01020304;
  h.sequence = 5;
  h.ack = 4;
  h.ack_bits = 0x3;
  h.ack_delay_ms = 0x0102;

  SECTION("header") {
    std::vector<std::uint8_t> out;
    write_header(h, out);
    const std::vector<std::uint8_t> golden = {'F', 'T', 'S', 'P', 0, 3, 0, 1, 2, 3, 4,
                                              0, 5, 0, 4, 0, 0, 0, 3, 1, 2};
    CHECK(out == golden);
  }
  SECTION("ping in JSON") {
    const auto bytes = encode_datagram(h, {Ping{}});
    const std::string payload(bytes.begin() + kHeaderBytes, bytes.end());
    CHECK(payload == R"([{"t":"ping"}])");
  }
  SECTION("command in JSON") {
    const auto bytes = encode_datagram(h, {Command{1, CommandOp::buy, 'm', {}, {}}});
    const std::string payload(bytes.begin() + kHeaderBytes, bytes.end());
    CHECK(payload == R"([{"t":"cmd","rid":1,"op":"buy","item":"m"}])");
  }
  SECTION("input in MessagePack") {
    h.encoding = Encoding::msgpack;
    const auto bytes = encode_datagram(h, {Input{3, {{4, 1, -1, true}}}});
    const std::vector<std::uint8_t> payload(bytes.begin() + kHeaderBytes, bytes.end());
    // [ {"t":"input", "ack":3, "f":[[4,1,-1,1]]} ]: "t" first, then the table's order
    const std::vector<std::uint8_t> golden = {0x91, 0x83, 0xA1, 't',  0xA5, 'i',  'n',  'p',
                                              'u',  't',  0xA3, 'a',  'c',  'k',  0x03, 0xA1,
                                              'f',  0x91, 0x94, 0x04, 0x01, 0xFF, 0x01};
    CHECK(payload == golden);
  }
}

TEST_CASE("to_json_text is the JSON payload", "[protocol][messages]") {
  CHECK(to_json_text({Bye{"quit"}}) == R"([{"t":"bye","reason":"quit"}])");
}
