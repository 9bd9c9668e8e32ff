// Cheap rejection (issue 12): nesting depth and value counts bounded while parsing, in
// both encodings, so that a deeply nested or lying payload is refused early.
#include <catch2/catch.hpp>

#include "harness.hpp"
#include "raw_datagrams.hpp"
#include "samples.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

Reject error_of(const std::vector<std::uint8_t>& bytes) {
  auto d = decode_datagram(bytes);
  REQUIRE_FALSE(d.ok());
  return d.error();
}

}  // namespace

TEST_CASE("Decode bounds: nesting deeper than the bound is out_of_range", "[protocol][reject][bounds]") {
  // Depth 5 is the deepest a message needs (snap -> players -> p); 6 parses, 7 does not.
  CHECK(error_of(raw_datagram(nested_json(kMaxNestingDepth), Encoding::json)) == Reject::garbage);
  CHECK(error_of(raw_datagram(nested_json(kMaxNestingDepth + 1), Encoding::json)) == Reject::out_of_range);
  CHECK(error_of(raw_datagram(nested_json(500), Encoding::json)) == Reject::out_of_range);
  CHECK(error_of(raw_datagram(nested_msgpack(kMaxNestingDepth - 1), Encoding::msgpack)) == Reject::garbage);
  CHECK(error_of(raw_datagram(nested_msgpack(kMaxNestingDepth), Encoding::msgpack)) == Reject::out_of_range);
  CHECK(error_of(raw_datagram(nested_msgpack(1100), Encoding::msgpack)) == Reject::out_of_range);
  // Objects count too.
  std::string objects;
  for (int i = 0; i < 20; ++i) objects += "{\"a\":";
  objects += "1" + std::string(20, '}');
  CHECK(error_of(raw_datagram(bytes_of("[" + objects + "]"), Encoding::json)) == Reject::out_of_range);
}

TEST_CASE("Decode bounds: a MessagePack container claiming more elements than bytes", "[protocol][reject][bounds]") {
  // array32 of 2^32-1 elements, then one element.
  CHECK(error_of(raw_datagram({0xdd, 0xff, 0xff, 0xff, 0xff, 0x01}, Encoding::msgpack)) == Reject::out_of_range);
  // map16 of 60000 pairs.
  CHECK(error_of(raw_datagram({0x91, 0xde, 0xea, 0x60, 0xa1, 't'}, Encoding::msgpack)) == Reject::out_of_range);
}

TEST_CASE("Decode bounds: every real message still decodes", "[protocol][reject][bounds]") {
  // all_messages() holds every message type, snapshots with players and events included
  // (the deepest payloads); the round trip runs through the bounded parser.
  for (auto enc : {Encoding::json, Encoding::msgpack}) {
    for (const auto& m : all_messages()) {
      Header h;
      h.encoding = enc;
      const auto bytes = encode_datagram(h, {m});
      if (bytes.size() > kMaxDatagramBytes) continue;
      auto d = decode_datagram(bytes);
      INFO(to_json_text({m}));
      REQUIRE(d.ok());
      CHECK(d->messages.at(0) == m);
    }
  }
}
