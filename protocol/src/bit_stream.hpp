// Bit streams for the packed parts of a message (the motion entries, PROTOCOL.md 8.2):
// a writer and a reader of Exp-Golomb codes (internal; wire_io.hpp's readers use them).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "fts/protocol/reject.hpp"

namespace fts::protocol::wire {

// ---- bit streams --------------------------------------------------------------------
// Exp-Golomb codes of order k (H.264's ue(v) generalised): n >= 0 takes
// 2 * bit_length(n + 2^k) - k - 1 bits, so small values are a few bits and nothing is
// ever out of reach. Signed values are zigzag-mapped first (0, -1, 1, -2, ... to 0, 1, 2, 3, ...).
inline std::uint64_t zigzag(std::int64_t v) {
  return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}
inline std::int64_t unzigzag(std::uint64_t u) {
  return static_cast<std::int64_t>(u >> 1) ^ -static_cast<std::int64_t>(u & 1);
}
inline unsigned golomb_bits(std::uint64_t n, unsigned k) {
  const std::uint64_t m = n + (std::uint64_t{1} << k);
  const unsigned len = static_cast<unsigned>(std::bit_width(m));
  return 2 * len - k - 1;
}

class BitWriter {
 public:
  explicit BitWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void bits(std::uint64_t v, unsigned n) {  // n <= 64, most significant first
    for (unsigned i = n; i > 0;) {
      const unsigned take = std::min(i, 8 - used_);
      i -= take;
      const auto chunk = static_cast<std::uint8_t>((v >> i) & ((1u << take) - 1));
      if (used_ == 0) out_.push_back(0);
      out_.back() = static_cast<std::uint8_t>(out_.back() | (chunk << (8 - used_ - take)));
      used_ = (used_ + take) % 8;
    }
  }
  void golomb(std::uint64_t n, unsigned k) {
    const std::uint64_t m = n + (std::uint64_t{1} << k);
    const unsigned len = static_cast<unsigned>(std::bit_width(m));
    bits(0, len - k - 1);
    bits(m, len);
  }

 private:
  std::vector<std::uint8_t>& out_;
  unsigned used_ = 0;  // bits used in the last byte (0: start a new one)
};

class BitReader {
 public:
  explicit BitReader(std::span<const std::uint8_t> b) : b_(b) {}
  bool failed() const { return failed_; }
  std::uint64_t bits(unsigned n) {
    if (n > 64 || pos_ + n > 8 * b_.size()) return failed_ = true, 0;
    std::uint64_t v = 0;
    while (n > 0) {
      const unsigned avail = 8 - static_cast<unsigned>(pos_ % 8);
      const unsigned take = std::min(n, avail);
      const unsigned byte = b_[pos_ / 8];
      v = (v << take) | ((byte >> (avail - take)) & ((1u << take) - 1));
      pos_ += take;
      n -= take;
    }
    return v;
  }
  // At most `max_bits` of value bits (a hostile run of zeros stops there).
  std::uint64_t golomb(unsigned k, unsigned max_bits = 48) {
    unsigned zeros = 0;
    for (;;) {
      if (failed_ || pos_ >= 8 * b_.size()) return failed_ = true, 0;
      const unsigned off = static_cast<unsigned>(pos_ % 8);
      const auto byte = static_cast<std::uint8_t>(b_[pos_ / 8] << off);
      const unsigned lz = byte == 0 ? 8 - off : static_cast<unsigned>(std::countl_zero(byte));
      zeros += lz;
      pos_ += lz;
      if (zeros + k + 1 > max_bits) return failed_ = true, 0;
      if (byte != 0) break;
    }
    const std::uint64_t m = bits(zeros + k + 1);
    // Bits that run out inside the code read as 0, not as 0 - 2^k (a huge value that
    // would overflow the caller's sums).
    if (failed_) return 0;
    return m - (std::uint64_t{1} << k);
  }
  // Only zero padding may follow the last value: fewer than 8 bits, all 0.
  bool rest_is_padding() const {
    const std::size_t left = 8 * b_.size() - pos_;
    return left < 8 && (left == 0 || (b_.back() & ((1u << left) - 1)) == 0);
  }

 private:
  std::span<const std::uint8_t> b_;
  std::size_t pos_ = 0;
  bool failed_ = false;
};

}  // namespace fts::protocol::wire
