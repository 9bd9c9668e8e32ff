// AgonesSync: the calls owed to the sidecar, in order, with the documented paths and
// bodies; a call not marked done is owed again (a retry), and only differences cost calls.
#include <catch2/catch.hpp>

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

AgonesWanted ready_with(std::uint32_t rooms, std::set<std::string> players) {
  AgonesWanted w;
  w.ready = true;
  w.version = "0.1.0";
  w.state.rooms = rooms;
  w.state.players = std::move(players);
  return w;
}

}  // namespace

TEST_CASE("AgonesSync: nothing is owed before the port is bound", "[fleet]") {
  AgonesSync sync;
  AgonesWanted w;
  auto c = sync.next(w);
  REQUIRE(c);  // labels and the counter are owed, but never Ready
  CHECK(c->op != SdkOp::ready);
  for (const auto& call : drain_calls(sync, w)) CHECK(call.rfind("POST /ready", 0) == std::string::npos);
}

TEST_CASE("AgonesSync: Ready, labels, the rooms Counter and the players List as documented", "[fleet]") {
  AgonesSync sync;
  const auto calls = drain_calls(sync, ready_with(1, {"ann", "bob"}));
  const std::vector<std::string> want = {
      "POST /ready {}",
      R"(PUT /metadata/label {"key":"phase","value":"lobby"})",
      R"(PUT /metadata/label {"key":"version","value":"0.1.0"})",
      R"(PATCH /v1beta1/counters/rooms {"count":"1"})",
      R"(POST /v1beta1/lists/players:addValue {"value":"ann"})",
      R"(POST /v1beta1/lists/players:addValue {"value":"bob"})",
  };
  CHECK(calls == want);
  SECTION("in step: nothing more is owed") { CHECK_FALSE(sync.next(ready_with(1, {"ann", "bob"}))); }
  SECTION("a player leaves and another comes: one remove, one add, removals first") {
    const auto more = drain_calls(sync, ready_with(1, {"bob", "cy"}));
    CHECK(more == std::vector<std::string>{R"(POST /v1beta1/lists/players:removeValue {"value":"ann"})",
                                           R"(POST /v1beta1/lists/players:addValue {"value":"cy"})"});
  }
  SECTION("everyone leaves: the counter goes to 0") {
    const auto more = drain_calls(sync, ready_with(0, {}));
    REQUIRE(more.size() == 3);
    CHECK(more[0] == R"(PATCH /v1beta1/counters/rooms {"count":"0"})");
  }
}

TEST_CASE("AgonesSync: a call not done stays owed (the retry)", "[fleet]") {
  AgonesSync sync;
  const auto w = ready_with(0, {});
  const auto first = sync.next(w);
  REQUIRE(first);
  CHECK(first->op == SdkOp::ready);
  const auto again = sync.next(w);  // the sidecar did not answer: the same call again
  REQUIRE(again);
  CHECK(again->op == SdkOp::ready);
  sync.done(*again);
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
  auto w = ready_with(1, {"ann"});
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
