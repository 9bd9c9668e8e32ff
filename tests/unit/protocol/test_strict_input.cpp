// Input PROTOCOL.md 3 and 4.9 reject is rejected (issue 36, point 3; each case was
// accepted before): a bin outside "mv", a JSON payload after a byte order mark, a key
// twice in an object (either encoding), a bye whose reason does not read.
#include <catch2/catch.hpp>

#include <string>

#include "fts/protocol/codec.hpp"

using namespace fts::protocol;

namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes text(const std::string& s) { return {s.begin(), s.end()}; }

Reject refused(Encoding enc, const Bytes& payload) {
  auto d = decode_payload(enc, payload);
  INFO((enc == Encoding::json ? std::string(payload.begin(), payload.end()) : std::string("(msgpack)")));
  REQUIRE_FALSE(d.ok());
  return d.error();
}

// MessagePack: fixstr s.
Bytes str(const std::string& s) {
  Bytes out{static_cast<std::uint8_t>(0xa0 | s.size())};
  out.insert(out.end(), s.begin(), s.end());
  return out;
}
Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}
const Bytes kBin8{0xc4, 0x03, 0x01, 0x02, 0x03};

}  // namespace

TEST_CASE("Strict input: a key twice is garbage, in JSON and MessagePack (PROTOCOL.md 3)", "[protocol][reject][strict]") {
  CHECK(refused(Encoding::json, text(R"([{"t":"ping","t":"ping"}])")) == Reject::garbage);
  // [{"t":"ping","t":"ping"}] in MessagePack.
  CHECK(refused(Encoding::msgpack, cat({{0x91, 0x82}, str("t"), str("ping"), str("t"), str("ping")})) == Reject::garbage);
  // An unknown key twice, and a key twice in an object inside a message.
  CHECK(refused(Encoding::json, text(R"([{"t":"ping","zz":1,"zz":1}])")) == Reject::garbage);
  CHECK(refused(Encoding::json, text(R"([{"t":"ping","zz":{"a":1,"a":2}}])")) == Reject::garbage);
  CHECK(refused(Encoding::msgpack, cat({{0x91, 0x82}, str("t"), str("ping"), str("zz"), {0x82}, str("a"), {1}, str("a"), {2}})) ==
        Reject::garbage);
  // A map of more keys than the decoder compares on the stack: the duplicate is the last.
  std::string many = R"([{"t":"ping")";
  for (int i = 0; i < 40; ++i) many += ",\"k" + std::to_string(i) + "\":0";
  CHECK(decode_payload(Encoding::json, text(many + "}]")).ok());
  CHECK(refused(Encoding::json, text(many + R"(,"k3":1}])")) == Reject::garbage);
  CHECK(refused(Encoding::json, text(many + R"(,"k39":1}])")) == Reject::garbage);
  // The same keys in two objects are fine.
  CHECK(decode_payload(Encoding::json, text(R"([{"t":"ping","zz":1},{"t":"ping","zz":1}])")).ok());
}

TEST_CASE("Strict input: a JSON payload after a UTF-8 byte order mark is garbage (PROTOCOL.md 3)",
          "[protocol][reject][strict]") {
  CHECK(decode_payload(Encoding::json, text(R"([{"t":"ping"}])")).ok());
  CHECK(refused(Encoding::json, text("\xEF\xBB\xBF" R"([{"t":"ping"}])")) == Reject::garbage);
}

TEST_CASE("Strict input: bin only in a snap's mv (PROTOCOL.md 3)", "[protocol][reject][strict]") {
  // [{"t":"ping"}] decodes; with a bin8 under a key ping does not know it does not.
  CHECK(decode_payload(Encoding::msgpack, cat({{0x91, 0x81}, str("t"), str("ping")})).ok());
  CHECK(refused(Encoding::msgpack, cat({{0x91, 0x82}, str("t"), str("ping"), str("zz"), kBin8})) == Reject::garbage);
  // Under "mv" in a message that has no mv, inside an array, inside an object.
  CHECK(refused(Encoding::msgpack, cat({{0x91, 0x82}, str("t"), str("ping"), str("mv"), kBin8})) == Reject::garbage);
  CHECK(refused(Encoding::msgpack, cat({{0x91, 0x82}, str("t"), str("ping"), str("zz"), {0x91}, kBin8})) == Reject::garbage);
  CHECK(refused(Encoding::msgpack, cat({{0x91, 0x82}, str("t"), str("ping"), str("zz"), {0x81}, str("mv"), kBin8})) ==
        Reject::garbage);
  // Where a bye's reason belongs.
  CHECK(refused(Encoding::msgpack, cat({{0x91, 0x82}, str("t"), str("bye"), str("reason"), kBin8})) == Reject::garbage);
}

TEST_CASE("Strict input: a bye whose reason does not read is refused (PROTOCOL.md 4.9)", "[protocol][reject][strict]") {
  const std::string ok200(200, 'q');
  auto d = decode_payload(Encoding::json, text(R"([{"t":"bye","reason":")" + ok200 + R"("}])"));
  REQUIRE(d.ok());
  CHECK(std::get<Bye>(d->at(0)).reason == ok200);
  CHECK(refused(Encoding::json, text(R"([{"t":"bye","reason":")" + ok200 + R"(q"}])")) == Reject::out_of_range);
  CHECK(refused(Encoding::json, text(R"([{"t":"bye","reason":"\u001b[2J"}])")) == Reject::out_of_range);
  CHECK(refused(Encoding::json, text(R"([{"t":"bye","reason":"tab\there"}])")) == Reject::out_of_range);
  CHECK(refused(Encoding::json, text(R"([{"t":"bye","reason":7}])")) == Reject::garbage);
  CHECK(refused(Encoding::msgpack, cat({{0x91, 0x82}, str("t"), str("bye"), str("reason"), {0x07}})) == Reject::garbage);
  CHECK(refused(Encoding::msgpack, cat({{0x91, 0x82}, str("t"), str("bye"), str("reason"), str("\x1b[2J")})) ==
        Reject::out_of_range);
  // The session goes on: a server test with sockets, tests/integration/test_abuse.py bad_bye;
  // a client's own reason is cleaned before it is sent (test_probe_bye.cpp).
}
