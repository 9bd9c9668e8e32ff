#include "json_reader.hpp"

#include <algorithm>
#include <array>

#include <nlohmann/json.hpp>

#include "wire_io.hpp"

namespace fts::protocol::wire {

namespace {

using json = nlohmann::json;

// nlohmann's SAX events written as MessagePack, with a gate: parsing stops at the first
// array or object nested deeper than kMaxNestingDepth, or at value number
// kMaxPayloadValues + 1. A hostile payload costs one partial pass over its bytes.
// JSON does not state container sizes up front: each container gets a 32-bit count that
// is filled in when it closes.
class SaxToMsgpack {
 public:
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  explicit SaxToMsgpack(std::vector<std::uint8_t>& out) : out_(out), w_(out) {}

  bool null() { return value() && (out_.push_back(0xc0), true); }
  bool boolean(bool v) { return value() && (w_.boolean(v), true); }
  bool number_integer(number_integer_t v) { return value() && (w_.integer(v), true); }
  bool number_unsigned(number_unsigned_t v) { return value() && (w_.uinteger(v), true); }
  bool number_float(number_float_t v, const string_t&) { return value() && (w_.number(v), true); }
  bool string(string_t& v) { return value() && (w_.str(v), true); }
  bool binary(binary_t&) { return false; }  // not in JSON text
  bool start_object(std::size_t) { return open(0xdf); }
  bool key(string_t& k) {
    ++open_[depth_ - 1].count;  // a map counts pairs: the key counts, its value not
    w_.str(k);
    after_key_ = true;
    return true;
  }
  bool end_object() { return close(); }
  bool start_array(std::size_t) { return open(0xdd); }
  bool end_array() { return close(); }
  template <class Exception>
  bool parse_error(std::size_t, const std::string&, const Exception&) {
    return false;
  }

  // Stopped by a bound (out_of_range) rather than by bad syntax (garbage).
  bool over_bound() const { return over_bound_; }

 private:
  struct Open {
    std::size_t at;  // offset of the container's header in out_
    std::uint32_t count;
  };
  bool value() {
    if (++values_ > kMaxPayloadValues) return over_bound_ = true, false;
    if (after_key_) after_key_ = false;
    else if (depth_ > 0) ++open_[depth_ - 1].count;
    return true;
  }
  bool open(std::uint8_t tag) {
    if (!value()) return false;
    if (depth_ >= kMaxNestingDepth) return over_bound_ = true, false;
    open_[depth_++] = {out_.size(), 0};
    out_.insert(out_.end(), {tag, 0, 0, 0, 0});
    return true;
  }
  bool close() {
    const Open o = open_[--depth_];
    for (int i = 0; i < 4; ++i) out_[o.at + 1 + i] = static_cast<std::uint8_t>(o.count >> (24 - 8 * i));
    return true;
  }

  std::vector<std::uint8_t>& out_;
  MsgpackWriter w_;
  std::array<Open, kMaxNestingDepth> open_{};
  std::size_t depth_ = 0;
  std::size_t values_ = 0;
  bool after_key_ = false;
  bool over_bound_ = false;
};

}  // namespace

bool json_to_msgpack(std::span<const std::uint8_t> text, std::vector<std::uint8_t>& out, Reject& why) {
  // nlohmann skips a UTF-8 byte order mark; PROTOCOL.md 3 says there is none.
  static constexpr std::array<std::uint8_t, 3> kBom{0xef, 0xbb, 0xbf};
  if (text.size() >= kBom.size() && std::equal(kBom.begin(), kBom.end(), text.begin()))
    return why = Reject::garbage, false;
  SaxToMsgpack sax(out);
  bool parsed = false;
  try {
    parsed = json::sax_parse(text.begin(), text.end(), &sax, json::input_format_t::json, /*strict=*/true);
  } catch (const json::exception&) {
    parsed = false;
  }
  if (parsed) return true;
  why = sax.over_bound() ? Reject::out_of_range : Reject::garbage;
  return false;
}

}  // namespace fts::protocol::wire
