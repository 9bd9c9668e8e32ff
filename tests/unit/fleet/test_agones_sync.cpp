// AgonesSync: the calls owed to the sidecar, in order, with the documented paths and
// bodies; a call not marked done is owed again (a retry), and only differences cost calls.
#include <catch2/catch.hpp>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "fleet/agones_sync.hpp"

using namespace fts::server;

namespace {

// Takes every owed call (each answered 2xx) and returns them as "METHOD path body".
std::vector<std::string> drain_calls(AgonesSync& sync, const AgonesWanted& w) {
  std::vector<std::string> out;
  for (int guard = 0; guard < 100; ++guard) {
    const auto c = sync.next(w);
    if (!c) return out;
    out.push_back(c->method + " " + c->path + " " + c->body);
    sync.done(*c);
  }
  FAIL("next() never ran out of calls");
  return out;
}

AgonesWanted ready_with(std::uint32_t seats, std::set<std::string> players, std::vector<std::string> codes = {}) {
  AgonesWanted w;
  w.ready = true;
  w.version = "0.1.0";
  w.state.rooms = static_cast<std::uint32_t>(codes.size());
  w.state.seats = seats;
  w.state.room_codes = std::move(codes);
  w.state.players = std::move(players);
  return w;
}

// The default limits' capacities (64 rooms of 8), owed before anything else.
const std::vector<std::string> kCapacityCalls = {
    R"(PATCH /v1beta1/counters/seats {"capacity":"512"})",
    R"(PATCH /v1beta1/lists/rooms {"capacity":"64"})",
    R"(PATCH /v1beta1/lists/players {"capacity":"512"})",
};

}  // namespace

TEST_CASE("AgonesSync: nothing is owed before the port is bound", "[fleet]") {
  AgonesSync sync;
  AgonesWanted w;
  auto c = sync.next(w);
  REQUIRE(c);  // labels and the counter are owed, but never Ready
  CHECK(c->op != SdkOp::ready);
  for (const auto& call : drain_calls(sync, w)) CHECK(call.rfind("POST /ready", 0) == std::string::npos);
}

TEST_CASE("AgonesSync: capacities, Ready, labels, the seats Counter and the Lists as documented", "[fleet]") {
  AgonesSync sync;
  const auto calls = drain_calls(sync, ready_with(2, {"ann", "bob"}, {"KXQPT"}));
  std::vector<std::string> want = kCapacityCalls;
  for (const char* c : {
           "POST /ready {}",
           R"(PUT /metadata/label {"key":"phase","value":"lobby"})",
           R"(PUT /metadata/label {"key":"version","value":"0.1.0"})",
           R"(PATCH /v1beta1/counters/seats {"count":"2"})",
           R"(POST /v1beta1/lists/rooms:addValue {"value":"KXQPT"})",
           R"(POST /v1beta1/lists/players:addValue {"value":"ann"})",
           R"(POST /v1beta1/lists/players:addValue {"value":"bob"})",
       })
    want.emplace_back(c);
  CHECK(calls == want);
  SECTION("in step: nothing more is owed") { CHECK_FALSE(sync.next(ready_with(2, {"ann", "bob"}, {"KXQPT"}))); }
  SECTION("a player leaves and another comes: one remove, one add, removals first") {
    const auto more = drain_calls(sync, ready_with(2, {"bob", "cy"}, {"KXQPT"}));
    CHECK(more == std::vector<std::string>{R"(POST /v1beta1/lists/players:removeValue {"value":"ann"})",
                                           R"(POST /v1beta1/lists/players:addValue {"value":"cy"})"});
  }
  SECTION("a room closes and another opens: the seats, then its code out before the new one in") {
    const auto more = drain_calls(sync, ready_with(3, {"ann", "bob"}, {"MNPQR"}));
    CHECK(more == std::vector<std::string>{R"(PATCH /v1beta1/counters/seats {"count":"3"})",
                                           R"(POST /v1beta1/lists/rooms:removeValue {"value":"KXQPT"})",
                                           R"(POST /v1beta1/lists/rooms:addValue {"value":"MNPQR"})"});
  }
  SECTION("everyone leaves: the counter goes to 0, the code and the names go") {
    const auto more = drain_calls(sync, ready_with(0, {}));
    CHECK(more == std::vector<std::string>{R"(PATCH /v1beta1/counters/seats {"count":"0"})",
                                           R"(POST /v1beta1/lists/rooms:removeValue {"value":"KXQPT"})",
                                           R"(POST /v1beta1/lists/players:removeValue {"value":"ann"})",
                                           R"(POST /v1beta1/lists/players:removeValue {"value":"bob"})"});
  }
}

TEST_CASE("AgonesSync: the capacities come from the server's limits, once", "[fleet]") {
  const auto small = agones_capacity(4, 8);
  CHECK(small.seats == 32);
  CHECK(small.rooms == 4);
  CHECK(small.players == 32);
  const auto big = agones_capacity(1024, 64);  // the largest the options allow
  CHECK(big.seats == 65536);
  CHECK(big.rooms == kAgonesListMax);  // Agones' List limit
  CHECK(big.players == kAgonesListMax);

  AgonesSync sync;
  auto w = ready_with(0, {});
  w.capacity = small;
  const auto calls = drain_calls(sync, w);
  REQUIRE(calls.size() >= 4);
  CHECK(std::vector<std::string>(calls.begin(), calls.begin() + 3) ==
        std::vector<std::string>{R"(PATCH /v1beta1/counters/seats {"capacity":"32"})",
                                 R"(PATCH /v1beta1/lists/rooms {"capacity":"4"})",
                                 R"(PATCH /v1beta1/lists/players {"capacity":"32"})"});
  CHECK(calls[3] == "POST /ready {}");  // never Ready before the capacities are right
  w.state.seats = 40;  // more than the capacity (cannot happen): the count stops at it
  CHECK(drain_calls(sync, w) == std::vector<std::string>{R"(PATCH /v1beta1/counters/seats {"count":"32"})"});
}

TEST_CASE("AgonesSync: every call owed once per difference, whatever the changes between", "[fleet]") {
  AgonesSync sync;
  auto w = ready_with(0, {});
  drain_calls(sync, w);
  // Ten rooms open; the HTTP thread makes two calls; five of them close again before it
  // looks next: one call per difference from what the sidecar holds, none for the rooms
  // that came and went.
  w = ready_with(10, {}, {"AAAAA", "BBBBB", "CCCCC", "DDDDD", "EEEEE", "FFFFF", "GGGGG", "HHHHH", "JJJJJ", "KKKKK"});
  for (int i = 0; i < 2; ++i) sync.done(*sync.next(w));  // the count 10, code AAAAA
  w = ready_with(5, {}, {"AAAAA", "CCCCC", "EEEEE", "GGGGG", "JJJJJ"});
  const auto calls = drain_calls(sync, w);
  CHECK(calls == std::vector<std::string>{R"(PATCH /v1beta1/counters/seats {"count":"5"})",
                                          R"(POST /v1beta1/lists/rooms:addValue {"value":"CCCCC"})",
                                          R"(POST /v1beta1/lists/rooms:addValue {"value":"EEEEE"})",
                                          R"(POST /v1beta1/lists/rooms:addValue {"value":"GGGGG"})",
                                          R"(POST /v1beta1/lists/rooms:addValue {"value":"JJJJJ"})"});
  CHECK(drain_calls(sync, w).empty());
  SECTION("a failed call is owed again, and only it") {
    w.state.room_codes = {"AAAAA", "CCCCC"};
    const auto c = sync.next(w);
    REQUIRE(c);
    CHECK(c->op == SdkOp::list_remove);
    const auto again = sync.next(w);  // not done: the same call
    REQUIRE(again);
    CHECK(again->body == c->body);
    CHECK(drain_calls(sync, w).size() == 3);
  }
}

TEST_CASE("AgonesSync: a List holds at most its capacity, older rooms first", "[fleet]") {
  AgonesSync sync;
  auto w = ready_with(0, {});
  w.capacity = agones_capacity(2, 8);
  drain_calls(sync, w);
  // Three rooms with a List of two (max_rooms past Agones' limit): the two oldest codes.
  w.state.room_codes = {"AAAAA", "BBBBB", "CCCCC"};
  CHECK(drain_calls(sync, w) == std::vector<std::string>{R"(POST /v1beta1/lists/rooms:addValue {"value":"AAAAA"})",
                                                         R"(POST /v1beta1/lists/rooms:addValue {"value":"BBBBB"})"});
  // The oldest closes: its place goes to the waiting code, the removal first, so the
  // sidecar never holds three (Agones would refuse the third).
  w.state.room_codes = {"BBBBB", "CCCCC"};
  CHECK(drain_calls(sync, w) == std::vector<std::string>{R"(POST /v1beta1/lists/rooms:removeValue {"value":"AAAAA"})",
                                                         R"(POST /v1beta1/lists/rooms:addValue {"value":"CCCCC"})"});
  SECTION("the bound holds after every single call") {
    AgonesSync s2;
    auto w2 = ready_with(0, {});
    w2.capacity = agones_capacity(2, 8);
    drain_calls(s2, w2);
    w2.state.room_codes = {"AAAAA", "BBBBB"};
    drain_calls(s2, w2);
    w2.state.room_codes = {"CCCCC", "DDDDD", "EEEEE"};
    int held = 2;
    for (int guard = 0; guard < 20; ++guard) {
      const auto c = s2.next(w2);
      if (!c) break;
      held += c->op == SdkOp::list_add ? 1 : c->op == SdkOp::list_remove ? -1 : 0;
      CHECK(held <= 2);
      s2.done(*c);
    }
    CHECK(held == 2);
  }
}

TEST_CASE("AgonesSync: a call not done stays owed (the retry)", "[fleet]") {
  AgonesSync sync;
  const auto w = ready_with(0, {});
  const auto first = sync.next(w);
  REQUIRE(first);
  CHECK(first->op == SdkOp::counter_capacity);
  const auto again = sync.next(w);  // the sidecar did not answer: the same call again
  REQUIRE(again);
  CHECK(again->op == SdkOp::counter_capacity);
  sync.done(*again);
  sync.done(*sync.next(w));  // the Lists' capacities
  sync.done(*sync.next(w));
  const auto ready = sync.next(w);
  REQUIRE(ready);
  CHECK(ready->op == SdkOp::ready);
  CHECK_FALSE(sync.ready_sent());
  sync.done(*ready);
  CHECK(sync.ready_sent());
  CHECK(sync.next(w)->op != SdkOp::ready);
}

TEST_CASE("AgonesSync: one Health per bump of the tick loop's sequence", "[fleet]") {
  AgonesSync sync;
  auto w = ready_with(0, {});
  drain_calls(sync, w);
  w.health_seq = 1;
  CHECK(drain_calls(sync, w) == std::vector<std::string>{"POST /health {}"});
  CHECK(drain_calls(sync, w).empty());
  w.health_seq = 5;  // several periods passed while the sidecar was away: one ping
  CHECK(drain_calls(sync, w) == std::vector<std::string>{"POST /health {}"});
}

TEST_CASE("AgonesSync: Shutdown comes last, after the final counts", "[fleet]") {
  AgonesSync sync;
  auto w = ready_with(1, {"ann"}, {"KXQPT"});
  drain_calls(sync, w);
  w = ready_with(0, {});
  w.state.phase = "draining";
  w.shutdown = true;
  const auto calls = drain_calls(sync, w);
  REQUIRE_FALSE(calls.empty());
  CHECK(calls.back() == "POST /shutdown {}");
  CHECK(calls.front() == R"(PUT /metadata/label {"key":"phase","value":"draining"})");
  CHECK(sync.shutdown_sent());
}

TEST_CASE("AgonesSync: names are JSON-escaped and label values made valid", "[fleet]") {
  AgonesSync sync;
  auto w = ready_with(1, {"a\"b"});
  w.version = "1.0+dev build";
  const auto calls = drain_calls(sync, w);
  CHECK(std::find(calls.begin(), calls.end(), R"(POST /v1beta1/lists/players:addValue {"value":"a\"b"})") !=
        calls.end());
  CHECK(std::find(calls.begin(), calls.end(), R"(PUT /metadata/label {"key":"version","value":"1.0-dev-build"})") !=
        calls.end());
}
