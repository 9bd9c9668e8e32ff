#include "fts/protocol/cookie.hpp"

#include <sodium.h>

#include <cstring>
#include <vector>

namespace fts::protocol {
namespace {

constexpr std::size_t kMacBytes = 16;

void put_u64(std::vector<std::uint8_t>& out, std::uint64_t v) {
  for (int i = 7; i >= 0; --i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

std::array<std::uint8_t, 32> keyed_hash(const ServerKey& key, std::string_view label,
                                        std::uint64_t number, std::string_view extra,
                                        std::size_t out_bytes) {
  ensure_sodium();
  std::vector<std::uint8_t> in(label.begin(), label.end());
  in.push_back(0);
  put_u64(in, number);
  in.insert(in.end(), extra.begin(), extra.end());
  std::array<std::uint8_t, 32> out{};
  crypto_generichash(out.data(), out_bytes, in.data(), in.size(), key.data(), key.size());
  return out;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

}  // namespace

void ensure_sodium() {
  // Idempotent and safe to call more than once; returns -1 only if the library is unusable.
  [[maybe_unused]] static const int ok = sodium_init();
}

bool from_hex(std::string_view hex, std::span<std::uint8_t> out) {
  if (hex.size() != 2 * out.size()) return false;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const int hi = hex_value(hex[2 * i]);
    const int lo = hex_value(hex[2 * i + 1]);
    if (hi < 0 || lo < 0) return false;
    out[i] = static_cast<std::uint8_t>(hi * 16 + lo);
  }
  return true;
}

std::string to_hex(const std::uint8_t* data, std::size_t size) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s;
  s.reserve(size * 2);
  for (std::size_t i = 0; i < size; ++i) {
    s.push_back(kDigits[data[i] >> 4]);
    s.push_back(kDigits[data[i] & 15]);
  }
  return s;
}

ServerKey random_key() {
  ensure_sodium();
  ServerKey key{};
  randombytes_buf(key.data(), key.size());
  return key;
}

std::string make_cookie(const ServerKey& key, std::string_view address, std::uint64_t now_ms) {
  std::uint8_t ts[8];
  for (int i = 0; i < 8; ++i) ts[i] = static_cast<std::uint8_t>(now_ms >> (8 * (7 - i)));
  const auto mac = keyed_hash(key, "cookie", now_ms, address, kMacBytes);
  return to_hex(ts, 8) + to_hex(mac.data(), kMacBytes);
}

CookieCheck check_cookie(const ServerKey& key, std::string_view address, std::string_view cookie,
                         std::uint64_t now_ms, std::uint64_t lifetime_ms) {
  std::uint8_t bytes[8 + kMacBytes];
  if (!from_hex(cookie, bytes)) return CookieCheck::forged;
  std::uint64_t issued_ms = 0;
  for (int i = 0; i < 8; ++i) issued_ms = (issued_ms << 8) | bytes[i];
  const auto mac = keyed_hash(key, "cookie", issued_ms, address, kMacBytes);
  if (sodium_memcmp(mac.data(), bytes + 8, kMacBytes) != 0) return CookieCheck::forged;
  if (issued_ms > now_ms || now_ms - issued_ms > lifetime_ms) return CookieCheck::expired;
  return CookieCheck::ok;
}

std::string derive_token(const ServerKey& key, std::uint64_t n) {
  const auto h = keyed_hash(key, "token", n, {}, 16);
  return to_hex(h.data(), 16);
}

std::array<std::uint8_t, 32> derive_kx_seed(const ServerKey& key) { return keyed_hash(key, "kx", 0, {}, 32); }

std::string token_verifier(std::string_view token) {
  ensure_sodium();
  std::array<std::uint8_t, 16> out{};
  crypto_generichash(out.data(), out.size(), reinterpret_cast<const unsigned char*>(token.data()), token.size(),
                     nullptr, 0);
  return to_hex(out.data(), out.size());
}

std::uint32_t derive_session_id(const ServerKey& key, std::uint64_t n) {
  const auto h = keyed_hash(key, "session", n, {}, 16);
  std::uint32_t id = 0;
  std::memcpy(&id, h.data(), sizeof id);
  return id == 0 ? 1 : id;
}

}  // namespace fts::protocol
