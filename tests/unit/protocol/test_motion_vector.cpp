// The packed motion entries against PROTOCOL.md 8.2.1 (issue 36): the test vector is read
// from the document itself, so the document, the C++ sender and the C++ reader cannot
// drift apart (tests/integration/sealed.py holds a client written from the document to
// the same block). The id gap is not zigzag-mapped; ex, ey, dvx, dvy are.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "fts/protocol/codec.hpp"

using namespace fts::protocol;

namespace {

struct MotionVector {
  std::vector<BallEntry> rows;
  std::vector<unsigned> orders;
  std::vector<std::uint8_t> bin;
};

std::vector<std::uint8_t> from_hex(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return out;
}

// The block after the heading "#### 8.2.1": its `rows`, `orders` and `bin` lines.
MotionVector vector_of_the_document() {
  std::ifstream in(std::string(FTS_SOURCE_DIR) + "/protocol/PROTOCOL.md");
  REQUIRE(in);
  std::string line;
  bool in_section = false;
  MotionVector v;
  while (std::getline(in, line)) {
    if (line.rfind("#### 8.2.1", 0) == 0) in_section = true;
    else if (in_section && line.rfind("#", 0) == 0) break;
    if (!in_section) continue;
    std::istringstream words(line);
    std::string what;
    words >> what;
    if (what == "rows") {
      std::string row;
      while (words >> row) {
        std::replace(row.begin(), row.end(), ',', ' ');
        std::istringstream nums(row.substr(1, row.size() - 2));  // inside [ ]
        BallEntry b;
        b.full = false;
        nums >> b.id >> b.x >> b.y >> b.vx >> b.vy;
        REQUIRE(nums);
        v.rows.push_back(b);
      }
    } else if (what == "orders") {
      for (unsigned k = 0; words >> k;) v.orders.push_back(k);
    } else if (what == "bin") {
      std::string hex;
      words >> hex;
      v.bin = from_hex(hex);
    }
  }
  REQUIRE(v.rows.size() == 5);
  REQUIRE(v.orders.size() == 5);
  REQUIRE(!v.bin.empty());
  return v;
}

SnapshotMsg delta_with(const std::vector<BallEntry>& motions) {
  SnapshotMsg m;
  m.tick = 105;
  m.base = 100;
  m.phase = Phase::play;
  m.level = 1;
  m.tick_rate_hz = 100;
  m.balls = motions;
  return m;
}

// The bytes of the "mv" value in a MessagePack payload: after the key a2 6d 76.
std::vector<std::uint8_t> mv_value(const std::vector<std::uint8_t>& payload) {
  static const std::vector<std::uint8_t> key{0xa2, 'm', 'v'};
  auto at = std::search(payload.begin(), payload.end(), key.begin(), key.end());
  REQUIRE(at != payload.end());
  return {at + 3, payload.end()};
}

}  // namespace

TEST_CASE("Motion vector: the sender writes PROTOCOL.md 8.2.1's bin, and reads it back", "[protocol][motion_vector]") {
  const MotionVector v = vector_of_the_document();
  const auto payload = encode_payload(Encoding::msgpack, {delta_with(v.rows)});
  const auto value = mv_value(payload);
  REQUIRE(value.size() >= 2 + v.bin.size());
  CHECK(value[0] == 0xc4);  // bin 8
  CHECK(value[1] == v.bin.size());
  CHECK(std::vector<std::uint8_t>(value.begin() + 2, value.begin() + 2 + static_cast<std::ptrdiff_t>(v.bin.size())) == v.bin);
  // The five orders, 6 bits each after the count (5 in order 3: 1101).
  std::uint64_t head = 0;
  for (int i = 0; i < 5; ++i) head = head << 8 | v.bin[static_cast<std::size_t>(i)];
  for (std::size_t s = 0; s < 5; ++s) CHECK(((head >> (40 - 4 - 6 * (s + 1))) & 63) == v.orders[s]);

  // The document's bytes, in a payload of their own, read as the rows (not zigzagged ids).
  std::vector<std::uint8_t> doc_payload(payload.begin(), payload.end() - static_cast<std::ptrdiff_t>(value.size()));
  doc_payload.push_back(0xc4);
  doc_payload.push_back(static_cast<std::uint8_t>(v.bin.size()));
  doc_payload.insert(doc_payload.end(), v.bin.begin(), v.bin.end());
  doc_payload.insert(doc_payload.end(), value.begin() + 2 + static_cast<std::ptrdiff_t>(v.bin.size()), value.end());
  auto d = decode_payload(Encoding::msgpack, doc_payload);
  REQUIRE(d.ok());
  CHECK(std::get<SnapshotMsg>(d->at(0)).balls == v.rows);
  // And in JSON, the same rows.
  auto j = decode_payload(Encoding::json, encode_payload(Encoding::json, {delta_with(v.rows)}));
  REQUIRE(j.ok());
  CHECK(std::get<SnapshotMsg>(j->at(0)).balls == v.rows);
}

TEST_CASE("Motion vector: a padding bit set is garbage", "[protocol][motion_vector][reject]") {
  const MotionVector v = vector_of_the_document();
  auto payload = encode_payload(Encoding::msgpack, {delta_with(v.rows)});
  const auto at = payload.size() - mv_value(payload).size() + 2 + v.bin.size() - 1;  // the bin's last byte
  REQUIRE(payload[at] == v.bin.back());
  payload[at] |= 1;  // 178 bits: the last 2 are padding
  auto d = decode_payload(Encoding::msgpack, payload);
  REQUIRE_FALSE(d.ok());
  CHECK(d.error() == Reject::garbage);
}

TEST_CASE("Motion vector: entries not in increasing id order travel as rows, in MessagePack too",
          "[protocol][motion_vector]") {
  // The id gap cannot be negative: such entries (make_delta never makes them) are written
  // in the other form a reader takes, never packed into wrong ids.
  std::vector<BallEntry> rows = vector_of_the_document().rows;
  std::swap(rows[1], rows[3]);
  rows.push_back(rows[0]);  // an id twice
  const auto payload = encode_payload(Encoding::msgpack, {delta_with(rows)});
  CHECK((mv_value(payload)[0] & 0xf0) == 0x90);  // a fixarray, not a bin
  CHECK(payload_bytes(Encoding::msgpack, {delta_with(rows)}) == payload.size());
  auto d = decode_payload(Encoding::msgpack, payload);
  REQUIRE(d.ok());
  CHECK(std::get<SnapshotMsg>(d->at(0)).balls == rows);
  // Id 0 first: its gap would be -1.
  std::vector<BallEntry> zero = {rows[0]};
  zero[0].id = 0;
  auto z = decode_payload(Encoding::msgpack, encode_payload(Encoding::msgpack, {delta_with(zero)}));
  REQUIRE(z.ok());
  CHECK(std::get<SnapshotMsg>(z->at(0)).balls == zero);
}
