// Issue 36.7: a Counter or List the sidecar does not take (an undeclared one: Agones answers
// 500) is retried on its own backoff beside the other calls; Ready, Health and Shutdown never
// wait for it. Time is stepped by hand (ms of the caller's clock).
#include <catch2/catch.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "fleet/agones_sync.hpp"
#include "fleet/update_retry.hpp"

using namespace fts::server;

namespace {

AgonesWanted wanted(std::uint32_t seats = 0, std::set<std::string> players = {}, std::vector<std::string> codes = {}) {
  AgonesWanted w;
  w.ready = true;
  w.version = "0.1.0";
  w.state.rooms = static_cast<std::uint32_t>(codes.size());
  w.state.seats = seats;
  w.state.room_codes = std::move(codes);
  w.state.players = std::move(players);
  return w;
}

// Answers every owed call at now_ms: those of `failing_row` fail, the others are taken.
// Returns the calls made, as "METHOD path" ("! " in front of a failed one).
std::vector<std::string> answer(AgonesSync& sync, const AgonesWanted& w, std::uint64_t now_ms,
                                std::optional<std::size_t> failing_row) {
  std::vector<std::string> out;
  for (int guard = 0; guard < 100; ++guard) {
    const auto c = sync.next(w, now_ms);
    if (!c) return out;
    const bool fail = c->row && c->row == failing_row;
    out.push_back((fail ? "! " : "") + c->method + " " + c->path);
    if (fail)
      sync.failed(*c, now_ms);
    else
      sync.done(*c);
  }
  FAIL("next() never ran out of calls");
  return out;
}

bool has(const std::vector<std::string>& calls, const std::string& call) {
  return std::find(calls.begin(), calls.end(), call) != calls.end();
}

}  // namespace

TEST_CASE("UpdateRetry: backoff doubles from min to max, a spell starts once and ends on success", "[fleet]") {
  UpdateRetry r(100, 1000);
  CHECK(r.due(0));
  CHECK_FALSE(r.failing());
  CHECK(r.failed(5000));  // the first failure starts the spell
  CHECK(r.failing());
  CHECK(r.backoff_ms() == 100);
  CHECK_FALSE(r.due(5099));
  CHECK(r.due(5100));
  std::uint64_t t = 5100;
  std::vector<std::uint32_t> waits;
  for (int i = 0; i < 6; ++i) {
    CHECK_FALSE(r.failed(t));  // the same spell: not logged again
    waits.push_back(r.backoff_ms());
    CHECK_FALSE(r.due(t + r.backoff_ms() - 1));
    t += r.backoff_ms();
    CHECK(r.due(t));
  }
  CHECK(waits == std::vector<std::uint32_t>{200, 400, 800, 1000, 1000, 1000});
  CHECK(r.spell() == 7);
  CHECK(r.spell_start_ms() == 5000);
  CHECK(r.succeeded() == 7);
  CHECK_FALSE(r.failing());
  CHECK(r.due(0));
  CHECK(r.succeeded() == 0);  // no spell to end
  CHECK(r.failed(t));         // a new spell, from the shortest wait again
  CHECK(r.backoff_ms() == 100);
  CHECK(r.total() == 8);
}

TEST_CASE("AgonesSync: an undeclared Counter holds neither Ready nor Health nor the Lists", "[fleet]") {
  AgonesSync sync(100, 2000);
  const auto w = wanted(1, {"ann"}, {"KXQPT"});
  // t = 0: the seats capacity fails; everything else is taken at once, Ready included.
  const auto first = answer(sync, w, 0, kSeatsRow);
  CHECK(first.front() == "! PATCH /v1beta1/counters/seats");
  CHECK(std::count(first.begin(), first.end(), "! PATCH /v1beta1/counters/seats") == 1);
  CHECK(has(first, "POST /ready"));
  CHECK(has(first, "PATCH /v1beta1/lists/rooms"));
  CHECK(has(first, "PATCH /v1beta1/lists/players"));
  CHECK(has(first, "POST /v1beta1/lists/rooms:addValue"));
  CHECK(has(first, "POST /v1beta1/lists/players:addValue"));
  CHECK(sync.ready_sent());
  CHECK(sync.retry(kSeatsRow).failing());
  CHECK_FALSE(sync.retry(kRoomsRow).failing());

  // Until the retry is due nothing is owed, and the client sleeps until then.
  CHECK_FALSE(sync.next(w, 99));
  CHECK(sync.next_retry_ms(99) == 100u);

  // Health comes every period whatever the Counter does.
  auto w2 = w;
  w2.health_seq = 1;
  const auto health = sync.next(w2, 50);
  REQUIRE(health);
  CHECK(health->op == SdkOp::health);
  sync.done(*health);

  // Retried at 100, 300, 700, 1500, 3100, 5100 (doubling, capped at 2 s).
  std::vector<std::uint64_t> tries;
  for (std::uint64_t t = 100; t <= 6000; ++t) {
    const auto c = sync.next(w2, t);
    if (!c) continue;
    REQUIRE(c->op == SdkOp::counter_capacity);
    tries.push_back(t);
    CHECK_FALSE(sync.failed(*c, t));  // one spell: only its first failure is logged
  }
  CHECK(tries == std::vector<std::uint64_t>{100, 300, 700, 1500, 3100, 5100});
  CHECK(sync.retry(kSeatsRow).spell() == 7);

  // Declared at last: the capacity, then the count; the spell is over.
  const auto rest = answer(sync, w2, 7100, std::nullopt);
  CHECK(rest == std::vector<std::string>{"PATCH /v1beta1/counters/seats", "PATCH /v1beta1/counters/seats"});
  CHECK_FALSE(sync.retry(kSeatsRow).failing());
  CHECK_FALSE(sync.next_retry_ms(7100));
  CHECK_FALSE(sync.next(w2, 7100));
}

TEST_CASE("AgonesSync: each Counter and List retries on its own", "[fleet]") {
  AgonesSync sync(100, 2000);
  auto w = wanted(2, {"ann", "bob"}, {"KXQPT"});
  const auto calls = answer(sync, w, 0, kRoomsRow);
  CHECK(calls.front() == "PATCH /v1beta1/counters/seats");
  CHECK(has(calls, "! PATCH /v1beta1/lists/rooms"));
  CHECK(has(calls, "PATCH /v1beta1/counters/seats"));
  CHECK(std::count(calls.begin(), calls.end(), "POST /v1beta1/lists/players:addValue") == 2);
  CHECK_FALSE(has(calls, "POST /v1beta1/lists/rooms:addValue"));  // waits for its List's retry
  // A player leaves while the rooms List waits: the players List follows at once.
  w.state.players = {"bob"};
  const auto c = sync.next(w, 10);
  REQUIRE(c);
  CHECK(c->path == "/v1beta1/lists/players:removeValue");
  CHECK(c->row == kPlayersRow);
}

TEST_CASE("AgonesSync: Shutdown does not wait for a failing List", "[fleet]") {
  AgonesSync sync(100, 2000);
  auto w = wanted(0, {}, {"KXQPT"});
  answer(sync, w, 0, kRoomsRow);
  w.shutdown = true;
  const auto c = sync.next(w, 1);
  REQUIRE(c);
  CHECK(c->op == SdkOp::shutdown);
  sync.done(*c);
  CHECK(sync.shutdown_sent());
}

TEST_CASE("AgonesSync: a failing row due already but owing nothing wakes nobody", "[fleet]") {
  AgonesSync sync(100, 2000);
  auto w = wanted(3);
  answer(sync, w, 0, std::nullopt);  // in step
  w.state.seats = 4;
  const auto c = sync.next(w, 10);
  REQUIRE(c);
  REQUIRE(c->op == SdkOp::counter);
  CHECK(sync.failed(*c, 10));
  CHECK(sync.next_retry_ms(10) == 110u);
  w.state.seats = 3;  // back to what the sidecar holds: nothing owed for the Counter
  CHECK_FALSE(sync.next(w, 200));
  CHECK_FALSE(sync.next_retry_ms(200));  // no wake-up for a row with nothing to send (no busy loop)
}

TEST_CASE("Fleet names: one table, the capacities the sync sets", "[fleet]") {
  CHECK(std::string(kFleetNames[kSeatsRow].name) == "seats");
  CHECK(kFleetNames[kSeatsRow].kind == FleetKind::counter);
  CHECK(fleet_row(FleetKind::list, "rooms") == kRoomsRow);
  CHECK(fleet_row(FleetKind::list, "players") == kPlayersRow);
  CHECK_FALSE(fleet_row(FleetKind::counter, "rooms"));
  const auto c = agones_capacity(1000, 8);
  CHECK(c.seats == 8000);
  CHECK(c.rooms == 1000);
  CHECK(c.players == 1000);
  const auto lines = fleet_names_json_lines(64, 8);
  CHECK(lines.find(R"("kind":"counter")") != std::string::npos);
  CHECK(lines.find(R"("capacity":512)") != std::string::npos);
  CHECK(std::count(lines.begin(), lines.end(), '\n') == static_cast<long>(kFleetNameCount));
}
