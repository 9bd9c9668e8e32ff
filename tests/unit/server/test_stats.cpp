// The stats line's tick-time figures, through the one percentile rule (fts/sim/percentile.hpp).
#include <catch2/catch.hpp>

#include "app/stats.hpp"
#include "fts/sim/percentile.hpp"

TEST_CASE("Stats: percentiles by nearest rank", "[server][stats]") {
  std::vector<double> v;
  for (int i = 100; i >= 1; --i) v.push_back(i);  // 1..100, reversed
  const auto p = fts::server::percentiles(v);
  CHECK(p.samples == 100);
  CHECK(p.p50_us == 51);  // rank round(0.5 * 99) = 50 (0-based)
  CHECK(p.p99_us == 99);
  CHECK(p.max_us == 100);
  std::vector<double> none;
  CHECK(fts::sim::percentile(none, 0.5) == 0);
  std::vector<double> one{7};
  CHECK(fts::sim::percentile(one, 0.99) == 7);
}

TEST_CASE("Stats: datagrams and bytes counted once, the interval is the totals' change", "[server][stats]") {
  fts::server::Stats s;
  s.received(100);
  s.sent(40);
  s.sent(60);
  CHECK(s.totals.datagrams_in == 1);
  CHECK(s.totals.bytes_out == 100);
  CHECK(s.interval().datagrams_out == 2);
  s.reset_interval();
  s.received(5);
  CHECK(s.interval().datagrams_in == 1);
  CHECK(s.interval().bytes_in == 5);
  CHECK(s.interval().datagrams_out == 0);
  CHECK(s.totals.datagrams_in == 2);
  CHECK(s.totals.bytes_in == 105);
}
