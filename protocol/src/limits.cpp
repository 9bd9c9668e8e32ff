#include "fts/protocol/limits.hpp"

#include <algorithm>

namespace fts::protocol {

TokenBucket::TokenBucket(std::uint32_t rate_per_s, std::uint32_t burst, std::uint64_t now_ms)
    : rate_per_s_(rate_per_s),
      capacity_milli_(std::uint64_t{burst} * 1000),
      level_milli_(capacity_milli_),
      last_ms_(now_ms) {}

std::uint64_t TokenBucket::level_at(std::uint64_t now_ms) const {
  if (now_ms <= last_ms_) return level_milli_;
  // rate_per_s tokens a second = rate_per_s thousandths a millisecond.
  const std::uint64_t gained = (now_ms - last_ms_) * rate_per_s_;
  return std::min(capacity_milli_, level_milli_ + gained);
}

bool TokenBucket::take(std::uint64_t now_ms) {
  level_milli_ = level_at(now_ms);
  last_ms_ = std::max(last_ms_, now_ms);
  if (level_milli_ < 1000) return false;
  level_milli_ -= 1000;
  return true;
}

bool TokenBucket::full(std::uint64_t now_ms) const { return level_at(now_ms) >= capacity_milli_; }

std::string_view host_of(std::string_view address) {
  if (!address.empty() && address.front() == '[') {
    const auto close = address.find(']');
    return close == std::string_view::npos ? address : address.substr(0, close + 1);
  }
  const auto colon = address.rfind(':');
  // Two colons or more without brackets: a bare IPv6 address, no port.
  if (colon == std::string_view::npos || address.find(':') != colon) return address;
  return address.substr(0, colon);
}

}  // namespace fts::protocol
