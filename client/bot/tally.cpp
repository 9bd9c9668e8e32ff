#include "bot/tally.hpp"

#include "fts/sim/percentile.hpp"

namespace fts::bot {

void Tally::on_snapshot(const protocol::Snapshot& s) {
  if (snapshots_ == 0) first_tick_ = s.tick;
  ++snapshots_;
  last_tick_ = s.tick;
}

void Tally::on_event(const protocol::Event& e, std::uint32_t me) {
  // Coins as the events tell them, to check against the coins in the snapshot.
  if (e.kind == protocol::EventKind::enemy_fell && e.b == me) earned_ += e.value;
  if (e.kind == protocol::EventKind::interest && e.a == me) earned_ += e.value;
  if (e.kind == protocol::EventKind::purchase && e.a == me) {
    spent_ += e.value;
    ++purchase_events_;
  }
}

void Tally::on_purchase_result(bool ok, char item) {
  (ok ? purchases_ok_ : purchases_refused_) += 1;
  if (ok) bought_.push_back(std::string(1, item));
}

void Tally::sample_rtt(double rtt_ms, std::uint64_t now_ms) {
  if (now_ms - last_rtt_sample_ms_ < kRttEveryMs) return;
  if (rtt_ms > 0) rtt_samples_.push_back(rtt_ms);
  last_rtt_sample_ms_ = now_ms;
}

std::uint64_t Tally::snapshots_lost(std::uint32_t ticks_per_snapshot) const {
  const std::uint64_t expected = snapshots_ ? (last_tick_ - first_tick_) / ticks_per_snapshot + 1 : 0;
  return expected > snapshots_ ? expected - snapshots_ : 0;
}

double Tally::rtt_percentile_ms(double q) const {
  std::vector<double> v = rtt_samples_;
  return sim::percentile(v, q);
}

}  // namespace fts::bot
