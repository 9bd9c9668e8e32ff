// The three writers and the one reader the field tables drive (internal): MessagePack
// written straight into a byte buffer, JSON text written straight into a string, a
// counter that measures either without writing (yojimbo's measure stream), and a
// MessagePack reader over untrusted bytes. No intermediate tree on any of these paths.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fts/protocol/constants.hpp"
#include "fts/protocol/reject.hpp"
#include "bit_stream.hpp"

namespace fts::protocol::wire {

// ---- MessagePack writer -------------------------------------------------------------
// Smallest representation of every value (PROTOCOL.md 3): non-negative integers as
// unsigned, floats as float32 when that is exact.
class MsgpackWriter {
 public:
  explicit MsgpackWriter(std::vector<std::uint8_t>& out) : out_(out) {}

  void array(std::size_t n) { header(n, 0x90, 0xdc, 0xdd); }
  void map(std::size_t n) { header(n, 0x80, 0xde, 0xdf); }
  void key(std::string_view k) { str(k); }
  void boolean(bool v) { out_.push_back(v ? 0xc3 : 0xc2); }
  void integer(std::int64_t v) {
    if (v >= 0) return uinteger(static_cast<std::uint64_t>(v));
    if (v >= -32) return out_.push_back(static_cast<std::uint8_t>(v));
    if (v >= INT8_MIN) return tagged(0xd0, static_cast<std::uint8_t>(v), 1);
    if (v >= INT16_MIN) return tagged(0xd1, static_cast<std::uint16_t>(v), 2);
    if (v >= INT32_MIN) return tagged(0xd2, static_cast<std::uint32_t>(v), 4);
    tagged(0xd3, static_cast<std::uint64_t>(v), 8);
  }
  void uinteger(std::uint64_t v) {
    if (v < 128) return out_.push_back(static_cast<std::uint8_t>(v));
    if (v <= UINT8_MAX) return tagged(0xcc, v, 1);
    if (v <= UINT16_MAX) return tagged(0xcd, v, 2);
    if (v <= UINT32_MAX) return tagged(0xce, v, 4);
    tagged(0xcf, v, 8);
  }
  void number(double v) {
    const float f = static_cast<float>(v);
    if (static_cast<double>(f) == v) return tagged(0xca, std::bit_cast<std::uint32_t>(f), 4);
    tagged(0xcb, std::bit_cast<std::uint64_t>(v), 8);
  }
  void bin(std::span<const std::uint8_t> b) {
    bin_header(b.size());
    out_.insert(out_.end(), b.begin(), b.end());
  }
  // A bin of n bytes that the caller appends to buffer() next.
  void bin_header(std::size_t n) {
    if (n <= UINT8_MAX) tagged(0xc4, n, 1);
    else if (n <= UINT16_MAX) tagged(0xc5, n, 2);
    else tagged(0xc6, n, 4);
  }
  std::vector<std::uint8_t>& buffer() { return out_; }
  // Bytes of a value encoded elsewhere.
  void raw(std::span<const std::uint8_t> bytes) { out_.insert(out_.end(), bytes.begin(), bytes.end()); }
  void str(std::string_view s) {
    if (s.size() < 32) out_.push_back(static_cast<std::uint8_t>(0xa0 | s.size()));
    else if (s.size() <= UINT8_MAX) tagged(0xd9, s.size(), 1);
    else if (s.size() <= UINT16_MAX) tagged(0xda, s.size(), 2);
    else tagged(0xdb, s.size(), 4);
    out_.insert(out_.end(), s.begin(), s.end());
  }

 private:
  void header(std::size_t n, std::uint8_t fix, std::uint8_t t16, std::uint8_t t32) {
    if (n < 16) out_.push_back(static_cast<std::uint8_t>(fix | n));
    else if (n <= UINT16_MAX) tagged(t16, n, 2);
    else tagged(t32, n, 4);
  }
  void tagged(std::uint8_t tag, std::uint64_t v, int bytes) {
    out_.push_back(tag);
    for (int i = bytes - 1; i >= 0; --i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::vector<std::uint8_t>& out_;
};

// Bytes a value takes in MessagePack, without writing it.
class MsgpackCounter {
 public:
  void array(std::size_t n) { bytes += n < 16 ? 1 : n <= UINT16_MAX ? 3 : 5; }
  void map(std::size_t n) { array(n); }
  void key(std::string_view k) { str(k); }
  void boolean(bool) { bytes += 1; }
  void integer(std::int64_t v) {
    if (v >= 0) return uinteger(static_cast<std::uint64_t>(v));
    bytes += v >= -32 ? 1 : v >= INT8_MIN ? 2 : v >= INT16_MIN ? 3 : v >= INT32_MIN ? 5 : 9;
  }
  void uinteger(std::uint64_t v) {
    bytes += v < 128 ? 1 : v <= UINT8_MAX ? 2 : v <= UINT16_MAX ? 3 : v <= UINT32_MAX ? 5 : 9;
  }
  void raw(std::span<const std::uint8_t> b) { bytes += b.size(); }
  void bin(std::span<const std::uint8_t> b) { bytes += b.size() + (b.size() <= UINT8_MAX ? 2 : b.size() <= UINT16_MAX ? 3 : 5); }
  void number(double v) { bytes += static_cast<double>(static_cast<float>(v)) == v ? 5 : 9; }
  void str(std::string_view s) {
    bytes += s.size() + (s.size() < 32 ? 1 : s.size() <= UINT8_MAX ? 2 : s.size() <= UINT16_MAX ? 3 : 5);
  }
  std::size_t bytes = 0;
};

// ---- JSON text writer ---------------------------------------------------------------
// Compact JSON (no whitespace). Numbers in the shortest form that reads back exactly.
class JsonWriter {
 public:
  explicit JsonWriter(std::string& out) : out_(out) {}

  void array(std::size_t n) { open('[', n); }
  void map(std::size_t n) { open('{', n); }
  void key(std::string_view k) {
    value_start();
    quoted(k);
    out_.push_back(':');
    after_key_ = true;
  }
  void boolean(bool v) {
    value_start();
    out_ += v ? "true" : "false";
    value_end();
  }
  void integer(std::int64_t v) { chars(v); }
  void uinteger(std::uint64_t v) { chars(v); }
  void number(double v) {
    if (!std::isfinite(v)) v = 0;
    chars(v);
  }
  void str(std::string_view s) {
    value_start();
    quoted(s);
    value_end();
  }
  // JSON text of a value encoded elsewhere.
  void raw(std::string_view text) {
    value_start();
    out_ += text;
    value_end();
  }

 private:
  struct Level {
    char close;
    std::size_t left;  // values (or keys) still to come
    bool first;
  };
  template <class T>
  void chars(T v) {
    value_start();
    std::array<char, 32> buf{};
    const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    out_.append(buf.data(), r.ptr);
    value_end();
  }
  void open(char c, std::size_t n) {
    value_start();
    out_.push_back(c);
    stack_[depth_++] = {c == '[' ? ']' : '}', n, true};
    close_done();
  }
  void value_start() {
    if (after_key_) {
      after_key_ = false;
      return;
    }
    if (depth_ == 0) return;
    Level& l = stack_[depth_ - 1];
    if (!l.first) out_.push_back(',');
    l.first = false;
  }
  void value_end() {
    if (depth_ == 0) return;
    Level& l = stack_[depth_ - 1];
    // A key and its value count once: the value ends the pair.
    --l.left;
    close_done();
  }
  void close_done() {
    while (depth_ > 0 && stack_[depth_ - 1].left == 0) {
      out_.push_back(stack_[--depth_].close);
      if (depth_ > 0) --stack_[depth_ - 1].left;
    }
  }
  void quoted(std::string_view s) {
    out_.push_back('"');
    for (char c : s) {
      const auto u = static_cast<unsigned char>(c);
      if (c == '"' || c == '\\') {
        out_.push_back('\\');
        out_.push_back(c);
      } else if (u < 0x20 || u == 0x7f || u > 0x7f) {
        static constexpr char kHex[] = "0123456789abcdef";
        out_ += "\\u00";
        out_.push_back(kHex[u >> 4]);
        out_.push_back(kHex[u & 15]);
      } else {
        out_.push_back(c);
      }
    }
    out_.push_back('"');
  }
  std::string& out_;
  std::array<Level, 16> stack_{};
  std::size_t depth_ = 0;
  bool after_key_ = false;
};

// ---- MessagePack reader -------------------------------------------------------------
// Reads untrusted bytes. The first failure sticks: every later read returns a default
// and the caller checks failed() once at the end (yojimbo's read stream). Never reads
// past the span.
class MsgpackReader {
 public:
  explicit MsgpackReader(std::span<const std::uint8_t> bytes) : b_(bytes) {}

  bool failed() const { return failed_; }
  Reject reason() const { return reason_; }
  void fail(Reject r) {
    if (!failed_) failed_ = true, reason_ = r;
    pos_ = b_.size();
  }
  std::size_t pos() const { return pos_; }
  void seek(std::size_t pos) { pos_ = pos < b_.size() ? pos : b_.size(); }
  // A tolerant field (fields.hpp) that could not be read: the failure is forgotten, the
  // value at `start` skipped (the payload was validated whole, so it can be) and counted.
  void skip_faulty(std::size_t start) {
    failed_ = false;
    reason_ = Reject::garbage;
    seek(start);
    skip();
    ++faults_;
  }
  std::size_t faults() const { return faults_; }
  std::span<const std::uint8_t> bytes(std::size_t from, std::size_t to) const { return b_.subspan(from, to - from); }
  bool at_end() const { return pos_ >= b_.size(); }
  std::size_t remaining() const { return b_.size() - pos_; }

  // Container headers: the element count, at most max_items (out_of_range beyond).
  std::size_t array(std::size_t max_items) { return container(false, max_items); }
  std::size_t map(std::size_t max_items) { return container(true, max_items); }
  // True (and the tag consumed) if the next value is an array / a map.
  bool next_is_array() const { return !at_end() && is_array_tag(b_[pos_]); }

  std::string_view str(std::size_t max_bytes) {
    if (at_end()) return fail(Reject::truncated), std::string_view{};
    const std::uint8_t t = b_[pos_];
    std::size_t n = 0;
    if ((t & 0xe0) == 0xa0) n = t & 0x1f, step(1);
    else if (t == 0xd9) n = be(1), step(2);
    else if (t == 0xda) n = be(2), step(3);
    else if (t == 0xdb) n = be(4), step(5);
    else return fail(Reject::garbage), std::string_view{};
    if (failed_ || n > remaining()) return fail(Reject::truncated), std::string_view{};
    if (n > max_bytes) return fail(Reject::out_of_range), std::string_view{};
    std::string_view s(reinterpret_cast<const char*>(b_.data() + pos_), n);
    step(n);
    return s;
  }
  // A bin value of at most max_bytes.
  std::span<const std::uint8_t> bin(std::size_t max_bytes) {
    if (at_end()) return fail(Reject::truncated), std::span<const std::uint8_t>{};
    const std::uint8_t t = b_[pos_];
    std::size_t n = 0;
    if (t == 0xc4) n = be(1), step(2);
    else if (t == 0xc5) n = be(2), step(3);
    else if (t == 0xc6) n = be(4), step(5);
    else return fail(Reject::garbage), std::span<const std::uint8_t>{};
    if (failed_ || n > remaining()) return fail(Reject::truncated), std::span<const std::uint8_t>{};
    if (n > max_bytes) return fail(Reject::out_of_range), std::span<const std::uint8_t>{};
    const auto out = b_.subspan(pos_, n);
    step(n);
    return out;
  }
  bool boolean() {
    if (at_end()) return fail(Reject::truncated), false;
    const std::uint8_t t = b_[pos_++];
    if (t == 0xc2 || t == 0xc3) return t == 0xc3;
    fail(Reject::garbage);
    return false;
  }
  // An integer in lo..hi; a float where an integer belongs is garbage.
  std::int64_t integer(std::int64_t lo, std::int64_t hi) {
    bool negative = false;
    std::uint64_t u = 0;
    if (!raw_integer(u, negative)) return fail(Reject::garbage), 0;
    if (negative) {
      const auto v = static_cast<std::int64_t>(u);
      if (v < lo || v > hi) return fail(Reject::out_of_range), 0;
      return v;
    }
    if (u > static_cast<std::uint64_t>(hi) || (lo > 0 && u < static_cast<std::uint64_t>(lo)))
      return fail(Reject::out_of_range), 0;
    return static_cast<std::int64_t>(u);
  }
  // A number (integer or float), finite, in lo..hi.
  double number(double lo, double hi) {
    if (at_end()) return fail(Reject::truncated), 0.0;
    double v = 0;
    const std::uint8_t t = b_[pos_];
    if (t == 0xca) {
      v = static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(be(4))));
      step(5);
    } else if (t == 0xcb) {
      v = std::bit_cast<double>(be(8));
      step(9);
    } else {
      bool negative = false;
      std::uint64_t u = 0;
      if (!raw_integer(u, negative)) return fail(Reject::garbage), 0.0;
      v = negative ? static_cast<double>(static_cast<std::int64_t>(u)) : static_cast<double>(u);
    }
    if (failed_) return 0.0;
    if (!std::isfinite(v) || v < lo || v > hi) return fail(Reject::out_of_range), 0.0;
    return v;
  }
  // Skips the value of a key the reader does not know; a bin there is garbage (bin is
  // only "mv", PROTOCOL.md 3).
  void skip_unknown() {
    if (!at_end() && b_[pos_] >= 0xc4 && b_[pos_] <= 0xc6) return fail(Reject::garbage);
    skip();
  }
  // Skips one value of any shape (already validated by validate()).
  void skip() {
    std::size_t depth = 0, values = 0;
    skip_value(depth, values, /*checked=*/false);
  }

  // Walks one whole value and enforces the payload bounds (PROTOCOL.md 10): nesting at
  // most kMaxNestingDepth, at most kMaxPayloadValues values, no container claiming more
  // elements than there are bytes left, no ext, no key twice in a map, bin only as a
  // message's "mv" (read_map refuses it under a key the message does not know). Leaves the
  // position unchanged.
  void validate_value() {
    const std::size_t start = pos_;
    std::size_t depth = 0, values = 0;
    skip_value(depth, values, /*checked=*/true);
    if (!failed_) pos_ = start;
  }

 private:
  static bool is_array_tag(std::uint8_t t) { return (t & 0xf0) == 0x90 || t == 0xdc || t == 0xdd; }
  static bool is_map_tag(std::uint8_t t) { return (t & 0xf0) == 0x80 || t == 0xde || t == 0xdf; }

  void step(std::size_t n) { pos_ = n > remaining() ? b_.size() : pos_ + n; }
  std::uint64_t be(std::size_t n) {
    if (pos_ + 1 + n > b_.size()) {
      fail(Reject::truncated);
      return 0;
    }
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) v = (v << 8) | b_[pos_ + 1 + i];
    return v;
  }

  bool raw_integer(std::uint64_t& u, bool& negative) {
    if (at_end()) return fail(Reject::truncated), true;
    const std::uint8_t t = b_[pos_];
    negative = false;
    if (t < 0x80) u = t, step(1);
    else if (t >= 0xe0) u = static_cast<std::uint64_t>(static_cast<std::int64_t>(static_cast<std::int8_t>(t))), negative = true, step(1);
    else if (t == 0xcc) u = be(1), step(2);
    else if (t == 0xcd) u = be(2), step(3);
    else if (t == 0xce) u = be(4), step(5);
    else if (t == 0xcf) u = be(8), step(9);
    else if (t >= 0xd0 && t <= 0xd3) {
      const std::size_t n = std::size_t{1} << (t - 0xd0);
      const std::uint64_t raw = be(n);
      step(1 + n);
      const int shift = static_cast<int>(64 - 8 * n);
      const auto v = static_cast<std::int64_t>(raw << shift) >> shift;  // sign-extend
      u = static_cast<std::uint64_t>(v);
      negative = v < 0;
    } else {
      return false;
    }
    return true;
  }

  std::size_t container(bool want_map, std::size_t max_items) {
    if (at_end()) return fail(Reject::truncated), 0;
    const std::uint8_t t = b_[pos_];
    if (want_map ? !is_map_tag(t) : !is_array_tag(t)) return fail(Reject::garbage), 0;
    std::size_t n = 0;
    if ((t & 0xf0) == 0x90 || (t & 0xf0) == 0x80) n = t & 0x0f, step(1);
    else if (t == 0xdc || t == 0xde) n = be(2), step(3);
    else n = be(4), step(5);
    if (failed_) return 0;
    if (n > max_items || n > remaining()) return fail(Reject::out_of_range), 0;
    return n;
  }

  // The pairs of a map being validated: string keys, each at most once (PROTOCOL.md 3,
  // either encoding: JSON objects arrive here as maps), a bin value only under "mv" in a
  // message (depth 2: the payload's list, then the message). The keys of a map of up to
  // kFewKeys are compared on the stack; a bigger one (no message has one) is sorted.
  static constexpr std::size_t kFewKeys = 32;
  void check_map(std::size_t n, std::size_t& depth, std::size_t& values) {
    std::array<std::string_view, kFewKeys> few;
    std::vector<std::string_view> many;
    for (std::size_t i = 0; i < n && !failed_; ++i) {
      if (++values > kMaxPayloadValues) return fail(Reject::out_of_range);
      if (at_end()) return fail(Reject::truncated);
      if (!is_str_tag(b_[pos_])) return fail(Reject::garbage);
      const std::string_view key = str(SIZE_MAX);
      if (failed_) return;
      if (i < kFewKeys) {
        for (std::size_t j = 0; j < i; ++j)
          if (few[j] == key) return fail(Reject::garbage);
        few[i] = key;
      } else {
        many.push_back(key);
      }
      skip_value(depth, values, /*checked=*/true, /*bin_ok=*/depth == 2 && key == "mv");
    }
    if (many.empty() || failed_) return;
    many.insert(many.end(), few.begin(), few.end());
    std::sort(many.begin(), many.end());
    if (std::adjacent_find(many.begin(), many.end()) != many.end()) fail(Reject::garbage);
  }

  void skip_value(std::size_t& depth, std::size_t& values, bool checked, bool bin_ok = false) {
    if (failed_) return;
    if (at_end()) return fail(Reject::truncated);
    if (checked && ++values > kMaxPayloadValues) return fail(Reject::out_of_range);
    const std::uint8_t t = b_[pos_];
    if (t < 0x80 || t >= 0xe0) return step(1);  // fixint, the most common value
    if (is_array_tag(t) || is_map_tag(t)) {
      const bool is_map = is_map_tag(t);
      if (checked && ++depth > kMaxNestingDepth) return fail(Reject::out_of_range);
      const std::size_t n = container(is_map, SIZE_MAX);
      if (checked && is_map) {
        check_map(n, depth, values);
      } else {
        for (std::size_t i = 0; i < n * (is_map ? 2 : 1) && !failed_; ++i) skip_value(depth, values, checked);
      }
      --depth;
      return;
    }
    if (is_str_tag(t)) {
      str(SIZE_MAX);
      return;
    }
    if (t >= 0xc4 && t <= 0xc6) {
      if (checked && !bin_ok) return fail(Reject::garbage);  // bin only in "mv" (PROTOCOL.md 3)
      bin(SIZE_MAX);
      return;
    }
    if (t == 0xc0 || t == 0xc2 || t == 0xc3) return step(1);  // nil only where the value is ignored
    if (t == 0xca || t == 0xcb) {
      const std::size_t n = t == 0xca ? 4 : 8;
      if (n + 1 > remaining()) return fail(Reject::truncated);
      step(1 + n);
      return;
    }
    std::uint64_t u = 0;
    bool negative = false;
    if (!raw_integer(u, negative)) return fail(Reject::garbage);  // nil, bin, ext, reserved
  }
  static bool is_str_tag(std::uint8_t t) { return (t & 0xe0) == 0xa0 || (t >= 0xd9 && t <= 0xdb); }

  std::span<const std::uint8_t> b_;
  std::size_t pos_ = 0;
  bool failed_ = false;
  std::size_t faults_ = 0;
  Reject reason_ = Reject::garbage;
};

}  // namespace fts::protocol::wire
