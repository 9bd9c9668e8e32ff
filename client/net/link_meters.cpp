#include "net/link_meters.hpp"

#include <algorithm>

namespace fts::client {

void LossMeter::on_snapshot(std::uint32_t tick, double ticks_per_snapshot) {
  if (last_tick_ != 0 && tick > last_tick_ && ticks_per_snapshot > 0) {
    expected_ += std::max(1.0, (tick - last_tick_) / ticks_per_snapshot);
    received_ += 1;
    if (expected_ > 100) {  // keep it recent
      expected_ /= 2;
      received_ /= 2;
    }
  }
  last_tick_ = tick;
}

double LossMeter::percent() const {
  return expected_ > 0 ? std::max(0.0, 100.0 * (1.0 - received_ / expected_)) : -1;
}

std::vector<protocol::Event> EventFeed::fresh(const protocol::Snapshot& s) {
  std::vector<protocol::Event> out;
  for (const auto& e : s.events)
    if (e.seq > last_seq_) out.push_back(e);
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.seq < b.seq; });
  if (!out.empty()) last_seq_ = out.back().seq;
  std::erase_if(out, [&](const auto& e) { return e.tick < since_tick_; });
  return out;
}

}  // namespace fts::client
