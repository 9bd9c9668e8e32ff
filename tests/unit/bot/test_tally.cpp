// A bot's report figures (bot/tally.hpp).
#include <catch2/catch.hpp>

#include "bot/tally.hpp"

using namespace fts;

TEST_CASE("Tally: snapshots lost from tick gaps, coins from events, purchases", "[bot][tally]") {
  bot::Tally t;
  protocol::Snapshot s;
  for (std::uint32_t tick : {5u, 10u, 20u, 25u}) {  // 15 is missing
    s.tick = tick;
    t.on_snapshot(s);
  }
  CHECK(t.snapshots() == 4);
  CHECK(t.snapshots_lost(5) == 1);
  t.on_event({1, 3, protocol::EventKind::enemy_fell, 9, 1, 40}, 1);  // we pushed it
  t.on_event({2, 4, protocol::EventKind::enemy_fell, 9, 2, 40}, 1);  // someone else did
  t.on_event({3, 5, protocol::EventKind::interest, 1, 0, 4}, 1);
  t.on_event({4, 6, protocol::EventKind::purchase, 1, 0, 30}, 1);
  CHECK(t.coins_earned() == 44);
  CHECK(t.coins_spent() == 30);
  CHECK(t.purchase_events() == 1);
  t.on_purchase_result(true, 'm');
  t.on_purchase_result(false, 'l');
  CHECK(t.purchases_ok() == 1);
  CHECK(t.purchases_refused() == 1);
  CHECK(t.bought() == std::vector<std::string>{"m"});
}

TEST_CASE("Tally: round trips sampled at most every 250 ms", "[bot][tally]") {
  bot::Tally t;
  CHECK(t.rtt_percentile_ms(0.5) == 0);
  t.sample_rtt(10, 1000);
  t.sample_rtt(500, 1100);  // too soon: not a sample
  t.sample_rtt(30, 1250);
  t.sample_rtt(0, 1500);    // not measured: no sample
  t.sample_rtt(20, 1600);   // too soon after the unmeasured one
  CHECK(t.rtt_percentile_ms(0.99) == 30);
  CHECK(t.rtt_percentile_ms(0.5) == 30);  // of {10, 30}: rank round(0.5) = 1
}
