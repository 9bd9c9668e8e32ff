#include "fts/protocol/identity.hpp"

#include <sodium.h>

#include <vector>

#include "fts/protocol/cookie.hpp"

namespace fts::protocol {
namespace {

static_assert(crypto_sign_SEEDBYTES == kIdentitySeedBytes && crypto_sign_PUBLICKEYBYTES == kIdentityPublicBytes);
static_assert(crypto_sign_BYTES == kIdentitySignatureBytes && crypto_sign_SECRETKEYBYTES == 64);

constexpr std::string_view kTranscriptLabel{"fts-identity-1\0", 15};
constexpr std::string_view kFileLabel = "fts-identity-1 ";
constexpr std::size_t kCookieBytes = 24;
constexpr std::size_t kBoxPlain = kIdentityPublicBytes + kIdentitySignatureBytes;

}  // namespace

Identity identity_from_seed(const std::array<std::uint8_t, kIdentitySeedBytes>& seed) {
  ensure_sodium();
  Identity id;
  id.seed = seed;
  crypto_sign_seed_keypair(id.public_key.data(), id.secret_key.data(), seed.data());
  return id;
}

Identity new_identity() {
  ensure_sodium();
  std::array<std::uint8_t, kIdentitySeedBytes> seed{};
  randombytes_buf(seed.data(), seed.size());
  Identity id = identity_from_seed(seed);
  sodium_memzero(seed.data(), seed.size());
  return id;
}

std::string fingerprint(const std::array<std::uint8_t, kIdentityPublicBytes>& public_key) {
  ensure_sodium();
  std::array<std::uint8_t, kFingerprintHex / 2> h{};
  crypto_generichash(h.data(), h.size(), public_key.data(), public_key.size(), nullptr, 0);
  return to_hex(h.data(), h.size());
}

std::optional<std::string> identity_transcript(std::string_view cookie_hex, const KxPublicKey& client_kx,
                                               const KxPublicKey& server_kx) {
  std::array<std::uint8_t, kCookieBytes> cookie{};
  if (!from_hex(cookie_hex, cookie)) return std::nullopt;
  std::string t(kTranscriptLabel);
  t.append(cookie.begin(), cookie.end());
  t.append(client_kx.begin(), client_kx.end());
  t.append(server_kx.begin(), server_kx.end());
  return t;
}

std::string seal_hello_identity(const Identity& id, const SessionKeys& client_keys, const KxPublicKey& client_kx,
                                const KxPublicKey& server_kx, std::string_view cookie_hex) {
  const auto transcript = identity_transcript(cookie_hex, client_kx, server_kx);
  if (!transcript) return {};
  std::array<std::uint8_t, kBoxPlain> plain{};
  std::copy(id.public_key.begin(), id.public_key.end(), plain.begin());
  crypto_sign_detached(plain.data() + kIdentityPublicBytes, nullptr,
                       reinterpret_cast<const unsigned char*>(transcript->data()), transcript->size(),
                       id.secret_key.data());
  std::vector<std::uint8_t> sealed;
  aead_seal(client_keys.tx, seal_nonce(SealDirection::hello_identity, 0), client_kx, plain, sealed);
  return to_hex(sealed.data(), sealed.size());
}

std::optional<std::string> open_hello_identity(const SessionKeys& server_keys, const KxPublicKey& client_kx,
                                               const KxPublicKey& server_kx, std::string_view cookie_hex,
                                               std::string_view sealed_hex) {
  std::array<std::uint8_t, kSealedIdentityHex / 2> sealed{};
  if (!from_hex(sealed_hex, sealed)) return std::nullopt;
  const auto transcript = identity_transcript(cookie_hex, client_kx, server_kx);
  if (!transcript) return std::nullopt;
  std::vector<std::uint8_t> plain;
  if (!aead_open(server_keys.rx, seal_nonce(SealDirection::hello_identity, 0), client_kx, sealed, plain) ||
      plain.size() != kBoxPlain)
    return std::nullopt;
  std::array<std::uint8_t, kIdentityPublicBytes> pk{};
  std::copy(plain.begin(), plain.begin() + kIdentityPublicBytes, pk.begin());
  if (crypto_sign_verify_detached(plain.data() + kIdentityPublicBytes,
                                  reinterpret_cast<const unsigned char*>(transcript->data()), transcript->size(),
                                  pk.data()) != 0)
    return std::nullopt;
  return fingerprint(pk);
}

std::string identity_file_text(const Identity& id) {
  return std::string(kFileLabel) + to_hex(id.seed.data(), id.seed.size()) + "\n";
}

std::optional<Identity> parse_identity_file(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.remove_suffix(1);
  if (text.substr(0, kFileLabel.size()) != kFileLabel) return std::nullopt;
  std::array<std::uint8_t, kIdentitySeedBytes> seed{};
  if (!from_hex(text.substr(kFileLabel.size()), seed)) return std::nullopt;
  Identity id = identity_from_seed(seed);
  sodium_memzero(seed.data(), seed.size());
  return id;
}

}  // namespace fts::protocol
