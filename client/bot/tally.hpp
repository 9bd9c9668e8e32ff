// What a bot's report states about its session: snapshots and their losses, round trips,
// coins as the events tell them, purchases. Fed by the bot; knows nothing of scripts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fts/protocol/snapshot.hpp"

namespace fts::bot {

class Tally {
 public:
  void on_snapshot(const protocol::Snapshot& s);
  // An event seen for the first time; `me` is our player id.
  void on_event(const protocol::Event& e, std::uint32_t me);
  void on_purchase_result(bool ok, char item);
  // A round-trip sample, at most every kRttEveryMs (0 or less: not measured yet).
  void sample_rtt(double rtt_ms, std::uint64_t now_ms);
  static constexpr std::uint64_t kRttEveryMs = 250;

  std::uint64_t snapshots() const { return snapshots_; }
  std::uint64_t snapshots_lost(std::uint32_t ticks_per_snapshot) const;
  double rtt_percentile_ms(double q) const;
  std::uint64_t purchases_ok() const { return purchases_ok_; }
  std::uint64_t purchases_refused() const { return purchases_refused_; }
  std::uint64_t purchase_events() const { return purchase_events_; }
  std::int64_t coins_earned() const { return earned_; }
  std::int64_t coins_spent() const { return spent_; }
  const std::vector<std::string>& bought() const { return bought_; }

 private:
  std::uint32_t first_tick_ = 0, last_tick_ = 0;
  std::uint64_t snapshots_ = 0;
  std::vector<double> rtt_samples_;
  std::uint64_t last_rtt_sample_ms_ = 0;
  std::int64_t earned_ = 0, spent_ = 0;
  std::uint64_t purchase_events_ = 0;
  std::uint64_t purchases_ok_ = 0, purchases_refused_ = 0;
  std::vector<std::string> bought_;
};

}  // namespace fts::bot
