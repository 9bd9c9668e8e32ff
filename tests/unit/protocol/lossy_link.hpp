// An in-memory one-way datagram link with seeded loss, duplication, latency and jitter
// (jitter reorders). Time is stepped by hand; nothing sleeps.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace fts::protocol::test {

struct LinkConfig {
  double loss = 0;          // probability a datagram is dropped
  double duplicate = 0;     // probability a delivered datagram arrives twice
  std::uint64_t latency_ms = 0;
  std::uint64_t jitter_ms = 0;  // extra delay, uniform in [0, jitter_ms]
  std::uint64_t seed = 1;
};

class LossyLink {
 public:
  explicit LossyLink(LinkConfig config = {}) : config_(config), state_(config.seed) {}

  void send(std::vector<std::uint8_t> bytes, std::uint64_t now_ms) {
    ++sent_;
    if (uniform() < config_.loss) {
      ++dropped_;
      return;
    }
    const int copies = uniform() < config_.duplicate ? 2 : 1;
    for (int i = 0; i < copies; ++i) {
      const auto jitter = config_.jitter_ms == 0 ? 0 : next() % (config_.jitter_ms + 1);
      in_flight_.push_back({now_ms + config_.latency_ms + jitter, order_++, bytes});
    }
  }

  // Datagrams due at now_ms, in arrival order.
  std::vector<std::vector<std::uint8_t>> receive(std::uint64_t now_ms) {
    std::stable_sort(in_flight_.begin(), in_flight_.end(), [](const auto& a, const auto& b) {
      return a.due_ms != b.due_ms ? a.due_ms < b.due_ms : a.order < b.order;
    });
    std::vector<std::vector<std::uint8_t>> out;
    auto it = in_flight_.begin();
    for (; it != in_flight_.end() && it->due_ms <= now_ms; ++it) out.push_back(std::move(it->bytes));
    in_flight_.erase(in_flight_.begin(), it);
    return out;
  }

  std::uint64_t sent() const { return sent_; }
  std::uint64_t dropped() const { return dropped_; }

 private:
  struct InFlight {
    std::uint64_t due_ms;
    std::uint64_t order;
    std::vector<std::uint8_t> bytes;
  };
  std::uint64_t next() {  // splitmix64: the same sequence on every platform
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) / 9007199254740992.0; }

  LinkConfig config_;
  std::uint64_t state_;
  std::uint64_t order_ = 0;
  std::uint64_t sent_ = 0, dropped_ = 0;
  std::vector<InFlight> in_flight_;
};

}  // namespace fts::protocol::test
