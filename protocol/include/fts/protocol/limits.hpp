// Rate limits on integer time (sans-I/O: "now" is passed in) and the host part of an
// address, which the per-address limits are keyed by (PROTOCOL.md 10).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace fts::protocol {

// A token bucket: `rate_per_s` tokens a second (or per_minute's a minute), at most
// `burst` kept. Counts in 1/60000 of a token, so that integer milliseconds refill it
// exactly at either rate.
class TokenBucket {
 public:
  TokenBucket() = default;
  TokenBucket(std::uint32_t rate_per_s, std::uint32_t burst, std::uint64_t now_ms);
  static TokenBucket per_minute(std::uint32_t rate_per_min, std::uint32_t burst, std::uint64_t now_ms);

  // Takes one token if there is one at now_ms.
  bool take(std::uint64_t now_ms);
  // Whether take() would succeed at now_ms (takes nothing).
  bool has(std::uint64_t now_ms) const;
  // Full at now_ms (its owner has been quiet long enough to be forgotten).
  bool full(std::uint64_t now_ms) const;

 private:
  static constexpr std::uint64_t kUnit = 60000;  // one token
  std::uint64_t level_at(std::uint64_t now_ms) const;

  std::uint64_t gain_per_ms_ = 0;  // in units: rate_per_s * 60, or rate_per_min
  std::uint64_t capacity_ = 0;
  std::uint64_t level_ = 0;
  std::uint64_t last_ms_ = 0;
};

// "192.0.2.7:40000" -> "192.0.2.7"; "[::1]:5000" -> "[::1]"; no port: the address itself.
std::string_view host_of(std::string_view address);

}  // namespace fts::protocol
