// Rate limits on integer time (sans-I/O: "now" is passed in) and the host part of an
// address, which the per-address limits are keyed by (PROTOCOL.md 10).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

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

// The per-host limits (PROTOCOL.md 10.1): a host's datagrams, its hellos, its reconnects
// that take a player over and its misses of room codes. The one part of the server's
// screening that the sessions of a host share; everything else is a session's own. At
// most `max_hosts` hosts are tracked: past it a new host is not limited until quiet ones
// are forgotten (forget_quiet, once a second), so that a spoofed flood cannot lock new
// players out.
class AddressLimits {
 public:
  struct Rates {
    std::uint32_t datagrams_per_s = 0, datagram_burst = 0;
    std::uint32_t hellos_per_s = 0, hello_burst = 0;
    std::uint32_t takeovers_per_s = 0, takeover_burst = 0;
    std::uint32_t code_misses_per_min = 0, code_miss_burst = 0;
    std::size_t max_hosts = 0;
  };
  struct Host {
    TokenBucket datagrams;
    TokenBucket hellos;
    TokenBucket takeovers;
    TokenBucket code_misses;  // room codes that named no open room
  };

  explicit AddressLimits(const Rates& rates) : rates_(rates) {}
  // `host`'s buckets (made full on first sight); nullptr while max_hosts are tracked. The
  // pointer stays valid until forget_quiet.
  Host* of(std::string_view host, std::uint64_t now_ms);
  // Forgets the hosts whose buckets are all full again (quiet for a while).
  void forget_quiet(std::uint64_t now_ms);
  std::size_t tracked() const { return entries_.size(); }

 private:
  // Looked up once for every datagram, in the serial part of a tick (issue 39): the hosts
  // in one deque (a host's name beside its datagrams' bucket, in one cache line), found
  // through an open-addressing table of their hashes and positions (8 bytes a slot, at most
  // half full: a few thousand hosts' slots stay in a core's cache). A std::unordered_map
  // node per host cost 3.6 simulated last-level misses per datagram (callgrind).
  struct alignas(64) Entry {
    std::string name;
    Host host;
  };
  struct Slot {
    std::uint32_t tag = 0;    // the hash's high half
    std::uint32_t entry = 0;  // position in entries_ + 1; 0: empty
  };
  void index(std::size_t position, std::uint64_t hash);
  void reindex();  // slots_ made again for entries_, sized for their count

  Rates rates_;
  std::deque<Entry> entries_;  // a deque: pointers to a host stay valid as hosts are added
  std::vector<Slot> slots_;    // a power of two
};

}  // namespace fts::protocol
