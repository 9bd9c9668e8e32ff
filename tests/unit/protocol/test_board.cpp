// The leaderboard on the wire (PROTOCOL.md 4.7c, issue 41): `cmd top` and `cmd forget`,
// and the `board` message made from its one field table: the document's example decodes,
// a full board fits a datagram in either encoding, and a board whose rows do not read
// (a hostile name, too many rows, a short row) does not decode.
#include <catch2/catch.hpp>

#include <fstream>
#include <set>
#include <string>

#include "fts/protocol/codec.hpp"
#include "fts/protocol/snapshot_delta.hpp"
#include "specs.hpp"

using namespace fts::protocol;

namespace {

Decoded<std::vector<Message>> json(const std::string& text) {
  return decode_payload(Encoding::json, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

Leaderboard full_board() {
  Leaderboard b;
  b.cmd = 0xFFFFFFFFu;
  for (std::uint32_t i = 1; i <= kBoardRows; ++i)
    b.top.push_back({0x7FFFFFFFu - i, std::string(kMaxNameBytes, static_cast<char>('a' + i)), 1'000'000, kMaxCoins});
  b.of = 0xFFFFFFFFu;
  b.rank = 0xFFFFFFFEu;
  b.best = 1'000'000;
  b.best_coins = kMaxCoins;
  return b;
}

}  // namespace

TEST_CASE("Board: the document's example decodes, and round-trips in both encodings", "[protocol][board]") {
  const auto d = json(R"([{"t":"board","cmd":3,"top":[[1,"ann",12,4500],[2,"bob",12,900]],"of":2,"rank":2,)"
                      R"("best":12,"best_coins":900}])");
  REQUIRE(d.ok());
  const Leaderboard want{3, {{1, "ann", 12, 4500}, {2, "bob", 12, 900}}, 2, 2, 12, 900};
  CHECK(std::get<Leaderboard>(d->at(0)) == want);
  // A guest's: no rank, best or coins of its own (absent on the wire, 0 when read).
  const auto g = json(R"([{"t":"board","cmd":1,"top":[],"of":0}])");
  REQUIRE(g.ok());
  CHECK(std::get<Leaderboard>(g->at(0)) == Leaderboard{1, {}, 0, 0, 0, 0});
  for (auto enc : {Encoding::json, Encoding::msgpack}) {
    for (const Leaderboard& b : {want, full_board(), Leaderboard{1, {}, 0, 0, 0, 0}}) {
      const auto again = decode_payload(enc, encode_payload(enc, {b}));
      REQUIRE(again.ok());
      CHECK(std::get<Leaderboard>(again->at(0)) == b);
    }
  }
}

TEST_CASE("Board: the fullest board fits one sealed datagram in either encoding", "[protocol][board]") {
  for (auto enc : {Encoding::json, Encoding::msgpack}) {
    INFO((enc == Encoding::json ? "json" : "msgpack"));
    CHECK(payload_bytes(enc, {full_board()}) <= kMaxPayloadBytes);
  }
}

TEST_CASE("Board: hostile names, too many rows and bad rows do not decode", "[protocol][board]") {
  const auto with_row = [](const std::string& row) {
    return json(R"([{"t":"board","cmd":3,"top":[)" + row + R"(],"of":1}])");
  };
  CHECK(with_row(R"([1,"ann",3,10])").ok());
  CHECK_FALSE(with_row(R"([1,"\u001b[2J",3,10])").ok());             // an escape
  CHECK_FALSE(with_row(R"([1,"a\u0007b",3,10])").ok());              // BEL
  CHECK_FALSE(with_row(R"([1,"\u65e5\u672c",3,10])").ok());          // not ASCII
  CHECK_FALSE(with_row(R"([1,"",3,10])").ok());                      // empty
  CHECK_FALSE(with_row(R"([1,"seventeen-chars-x",3,10])").ok());     // over 16 bytes
  CHECK_FALSE(with_row(R"([0,"ann",3,10])").ok());                   // rank 0
  CHECK_FALSE(with_row(R"([1,"ann",-1,10])").ok());                  // a negative level
  CHECK_FALSE(with_row(R"([1,"ann",3])").ok());                      // a short row
  CHECK_FALSE(with_row(R"([1,"ann",3,10,5])").ok());                 // a long one
  std::string eleven;
  for (int i = 1; i <= 11; ++i) eleven += (i > 1 ? "," : "") + std::string("[") + std::to_string(i) + R"(,"ann",3,10])";
  CHECK_FALSE(with_row(eleven).ok());
  CHECK_FALSE(json(R"([{"t":"board","top":[],"of":1}])").ok());  // no cmd
}

TEST_CASE("Board: PROTOCOL.md 4.7c lists exactly the board's keys, and its row's fields in order",
          "[protocol][board]") {
  std::set<std::string> keys;
  std::apply([&](const auto&... f) { (keys.emplace(f.key), ...); }, wire::kLeaderboardFields);
  std::string row;
  std::apply([&](const auto&... f) { ((row += (row.empty() ? "" : ", ") + std::string(f.key)), ...); }, wire::kBoardRow);
  std::ifstream in(std::string(FTS_SOURCE_DIR) + "/protocol/PROTOCOL.md");
  REQUIRE(in);
  std::set<std::string> documented;
  std::string line, section;
  bool in_section = false;
  while (std::getline(in, line)) {
    if (line.rfind("### 4.7c ", 0) == 0) in_section = true;
    else if (in_section && line.rfind("#", 0) == 0) break;
    if (!in_section) continue;
    section += line + "\n";
    if (line.rfind("| `", 0) != 0) continue;
    const std::size_t end = line.find('`', 3);
    documented.insert(line.substr(3, end - 3));
  }
  CHECK(documented == keys);
  CHECK(section.find("`[" + row + "]`") != std::string::npos);  // "[rank, name, level, coins]"
}

TEST_CASE("Board: top and forget are commands a server knows", "[protocol][board]") {
  const auto d = json(R"([{"t":"cmd","rid":4,"op":"top"},{"t":"cmd","rid":5,"op":"forget"}])");
  REQUIRE(d.ok());
  CHECK(std::get<Command>(d->at(0)).op == CommandOp::top);
  CHECK(std::get<Command>(d->at(1)).op == CommandOp::forget);
  for (auto enc : {Encoding::json, Encoding::msgpack}) {
    const auto again = decode_payload(enc, encode_payload(enc, {Command{7, CommandOp::forget, 0, {}, {}}}));
    REQUIRE(again.ok());
    CHECK(std::get<Command>(again->at(0)).op == CommandOp::forget);
  }
}
