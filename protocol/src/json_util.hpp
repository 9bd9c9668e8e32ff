// Strict field readers for the nlohmann mappings: a wrong shape throws DecodeFail with a
// reason, which the codec catches (nothing escapes to the caller of decode).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "fts/protocol/reject.hpp"

namespace fts::protocol::detail {

using json = nlohmann::json;

struct DecodeFail {
  Reject reason;
};

[[noreturn]] inline void fail(Reject reason) { throw DecodeFail{reason}; }

inline const json& field(const json& j, const char* key) {
  if (!j.is_object()) fail(Reject::garbage);
  auto it = j.find(key);
  if (it == j.end()) fail(Reject::garbage);
  return *it;
}

inline const json* optional_field(const json& j, const char* key) {
  auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}

inline std::int64_t as_int(const json& j, std::int64_t lo, std::int64_t hi) {
  if (j.is_number_unsigned()) {
    const auto u = j.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(hi) || (lo > 0 && u < static_cast<std::uint64_t>(lo)))
      fail(Reject::out_of_range);
    return static_cast<std::int64_t>(u);
  }
  if (!j.is_number_integer()) fail(Reject::garbage);
  const auto v = j.get<std::int64_t>();
  if (v < lo || v > hi) fail(Reject::out_of_range);
  return v;
}

inline std::uint32_t as_u32(const json& j, std::uint32_t hi = 0xFFFFFFFFu) {
  return static_cast<std::uint32_t>(as_int(j, 0, hi));
}

inline double as_double(const json& j, double lo, double hi) {
  if (!j.is_number()) fail(Reject::garbage);
  const double v = j.get<double>();
  if (!std::isfinite(v) || v < lo || v > hi) fail(Reject::out_of_range);
  return v;
}

inline bool as_bool(const json& j) {
  if (!j.is_boolean()) fail(Reject::garbage);
  return j.get<bool>();
}

// Printable ASCII only (so that logs and terminals are safe), at most max_bytes.
inline std::string as_text(const json& j, std::size_t max_bytes) {
  if (!j.is_string()) fail(Reject::garbage);
  const auto& s = j.get_ref<const std::string&>();
  if (s.size() > max_bytes) fail(Reject::out_of_range);
  for (unsigned char c : s)
    if (c < 0x20 || c > 0x7E) fail(Reject::out_of_range);
  return s;
}

// "" or exactly `digits` lower-case hex digits.
inline std::string as_hex(const json& j, std::size_t digits) {
  if (!j.is_string()) fail(Reject::garbage);
  const auto& s = j.get_ref<const std::string&>();
  if (s.empty()) return s;
  if (s.size() != digits) fail(Reject::out_of_range);
  for (char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) fail(Reject::out_of_range);
  return s;
}

inline const json& as_array(const json& j, std::size_t max_items) {
  if (!j.is_array()) fail(Reject::garbage);
  if (j.size() > max_items) fail(Reject::out_of_range);
  return j;
}

}  // namespace fts::protocol::detail
