#include "app/handover_frame.hpp"

#include <sodium.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

namespace fts::server::handover {

static_assert(kMacBytes == crypto_auth_hmacsha256_BYTES);

std::string key_of_secret(std::string_view secret) {
  std::string key(crypto_generichash_BYTES, '\0');
  crypto_generichash(reinterpret_cast<unsigned char*>(key.data()), key.size(),
                     reinterpret_cast<const unsigned char*>(secret.data()), secret.size(), nullptr, 0);
  return key;
}

std::string read_secret_file(const std::string& path, std::string& why) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    why = "--fleet-secret: cannot read " + path + ": " + std::strerror(errno);
    return "";
  }
  if ((st.st_mode & 077) != 0) {
    why = "--fleet-secret: " + path + " may be read by others than its owner (chmod 600 it)";
    return "";
  }
  std::ifstream in(path, std::ios::binary);
  const std::string secret((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (secret.size() < kSecretMinBytes) {
    why = "--fleet-secret: " + path + " holds " + std::to_string(secret.size()) + " bytes; at least " +
          std::to_string(kSecretMinBytes) + " are needed (head -c 32 /dev/urandom > FILE)";
    return "";
  }
  return key_of_secret(secret);
}

std::array<std::uint8_t, kMacBytes> mac(const std::string& key, std::string_view label, const Bytes& challenge,
                                        std::string_view json) {
  crypto_auth_hmacsha256_state st;
  crypto_auth_hmacsha256_init(&st, reinterpret_cast<const unsigned char*>(key.data()), key.size());
  crypto_auth_hmacsha256_update(&st, reinterpret_cast<const unsigned char*>(label.data()), label.size());
  crypto_auth_hmacsha256_update(&st, challenge.data(), challenge.size());
  crypto_auth_hmacsha256_update(&st, reinterpret_cast<const unsigned char*>(json.data()), json.size());
  std::array<std::uint8_t, kMacBytes> out{};
  crypto_auth_hmacsha256_final(&st, out.data());
  return out;
}

Bytes frame(const std::string& key, std::string_view label, const Bytes& challenge, std::string_view json) {
  // One allocation, filled in place (vector::insert of the JSON after the length made
  // g++ 12 at -O2 warn of a copy out of bounds that is not there).
  Bytes out(4 + json.size() + kMacBytes);
  const auto n = static_cast<std::uint32_t>(json.size());
  for (std::size_t i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>(n >> (24 - 8 * i));
  if (!json.empty()) std::memcpy(out.data() + 4, json.data(), json.size());
  const auto m = mac(key, label, challenge, json);
  std::memcpy(out.data() + 4 + json.size(), m.data(), kMacBytes);
  return out;
}

std::uint32_t frame_length(const std::array<std::uint8_t, 4>& b) {
  return (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) | b[3];
}

std::optional<std::string> open_body(const std::string& key, std::string_view label, const Bytes& challenge,
                                     const Bytes& body) {
  if (body.size() < kMacBytes) return std::nullopt;
  std::string json(body.begin(), body.end() - static_cast<std::ptrdiff_t>(kMacBytes));
  const auto want = mac(key, label, challenge, json);
  if (sodium_memcmp(want.data(), body.data() + json.size(), kMacBytes) != 0) return std::nullopt;
  return json;
}

}  // namespace fts::server::handover
