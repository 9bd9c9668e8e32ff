#include "fts/protocol/limits.hpp"

#include <algorithm>
#include <functional>

namespace fts::protocol {

TokenBucket::TokenBucket(std::uint32_t rate_per_s, std::uint32_t burst, std::uint64_t now_ms)
    : gain_per_ms_(std::uint64_t{rate_per_s} * kUnit / 1000),
      capacity_(std::uint64_t{burst} * kUnit),
      level_(capacity_),
      last_ms_(now_ms) {}

TokenBucket TokenBucket::per_minute(std::uint32_t rate_per_min, std::uint32_t burst, std::uint64_t now_ms) {
  TokenBucket b(0, burst, now_ms);
  b.gain_per_ms_ = std::uint64_t{rate_per_min} * kUnit / 60000;
  return b;
}

std::uint64_t TokenBucket::level_at(std::uint64_t now_ms) const {
  if (now_ms <= last_ms_) return level_;
  return std::min(capacity_, level_ + (now_ms - last_ms_) * gain_per_ms_);
}

bool TokenBucket::take(std::uint64_t now_ms) {
  level_ = level_at(now_ms);
  last_ms_ = std::max(last_ms_, now_ms);
  if (level_ < kUnit) return false;
  level_ -= kUnit;
  return true;
}

bool TokenBucket::has(std::uint64_t now_ms) const { return level_at(now_ms) >= kUnit; }

bool TokenBucket::full(std::uint64_t now_ms) const { return level_at(now_ms) >= capacity_; }

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

namespace {
std::uint64_t hash_of(std::string_view host) { return std::hash<std::string_view>{}(host); }
std::uint32_t tag_of(std::uint64_t hash) { return static_cast<std::uint32_t>(hash >> 32); }
}  // namespace

AddressLimits::Host* AddressLimits::of(std::string_view host, std::uint64_t now_ms) {
  const std::uint64_t hash = hash_of(host);
  const std::size_t mask = slots_.size() - 1;
  if (!slots_.empty())
    for (std::size_t i = hash & mask; slots_[i].entry != 0; i = (i + 1) & mask)
      if (slots_[i].tag == tag_of(hash)) {
        Entry& e = entries_[slots_[i].entry - 1];
        if (e.name == host) return &e.host;
      }
  if (entries_.size() >= rates_.max_hosts) return nullptr;
  const Rates& r = rates_;
  entries_.push_back(Entry{std::string(host),
                           Host{TokenBucket(r.datagrams_per_s, r.datagram_burst, now_ms),
                                TokenBucket(r.hellos_per_s, r.hello_burst, now_ms),
                                TokenBucket(r.takeovers_per_s, r.takeover_burst, now_ms),
                                TokenBucket::per_minute(r.code_misses_per_min, r.code_miss_burst, now_ms)}});
  if (entries_.size() * 2 > slots_.size()) reindex();  // (it indexes the new entry too)
  else index(entries_.size() - 1, hash);
  return &entries_.back().host;
}

void AddressLimits::index(std::size_t position, std::uint64_t hash) {
  const std::size_t mask = slots_.size() - 1;
  std::size_t i = hash & mask;
  while (slots_[i].entry != 0) i = (i + 1) & mask;
  slots_[i] = {tag_of(hash), static_cast<std::uint32_t>(position + 1)};
}

void AddressLimits::reindex() {
  std::size_t size = 16;
  while (size < entries_.size() * 2) size *= 2;
  slots_.assign(size, Slot{});
  for (std::size_t at = 0; at < entries_.size(); ++at) index(at, hash_of(entries_[at].name));
}

void AddressLimits::forget_quiet(std::uint64_t now_ms) {
  const auto erased = std::erase_if(entries_, [&](const Entry& e) {
    const Host& h = e.host;
    return h.datagrams.full(now_ms) && h.hellos.full(now_ms) && h.takeovers.full(now_ms) && h.code_misses.full(now_ms);
  });
  if (erased != 0) reindex();
}

}  // namespace fts::protocol
