// A player's long-term identity (issue 41, PROTOCOL.md 5.8): an Ed25519 key pair the
// client keeps (like an ssh key) and proves it holds in its cookie hello. The proof is a
// signature over this handshake (the server's cookie and both crypto_kx keys), sent with
// the public key inside a box sealed with the attempt's session key, so that neither the
// key nor the signature is ever seen on the path. The server knows the player by the
// key's fingerprint: profiles are keyed by it, never by the name. No identity: a guest.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "fts/protocol/seal.hpp"

namespace fts::protocol {

inline constexpr std::size_t kIdentitySeedBytes = 32;
inline constexpr std::size_t kIdentityPublicBytes = 32;
inline constexpr std::size_t kIdentitySignatureBytes = 64;
// The hello's `id`: the sealed public key and signature, in hex (2 * (32 + 64 + 16)).
inline constexpr std::size_t kSealedIdentityHex = 2 * (kIdentityPublicBytes + kIdentitySignatureBytes + 16);
inline constexpr std::size_t kFingerprintHex = 32;

struct Identity {
  std::array<std::uint8_t, kIdentitySeedBytes> seed{};  // the secret: the key pair is derived from it
  std::array<std::uint8_t, kIdentityPublicBytes> public_key{};
  std::array<std::uint8_t, 64> secret_key{};  // libsodium's form (seed || public key)
};

// crypto_sign_seed_keypair; a new identity takes randombytes_buf's seed.
Identity identity_from_seed(const std::array<std::uint8_t, kIdentitySeedBytes>& seed);
Identity new_identity();

// 32 hex digits: BLAKE2b-128 (unkeyed) of the 32-byte public key.
std::string fingerprint(const std::array<std::uint8_t, kIdentityPublicBytes>& public_key);
inline std::string fingerprint(const Identity& id) { return fingerprint(id.public_key); }

// What is signed: "fts-identity-1" 0x00, the cookie's 24 bytes, the client's and the
// server's crypto_kx public keys (103 bytes). nullopt for a cookie that is not 48 hex digits.
std::optional<std::string> identity_transcript(std::string_view cookie_hex, const KxPublicKey& client_kx,
                                               const KxPublicKey& server_kx);

// The hello's `id` (224 hex digits): public key || signature sealed with the client's tx
// key, nonce (hello_identity, 0), the client's kx public key as associated data.
std::string seal_hello_identity(const Identity& id, const SessionKeys& client_keys, const KxPublicKey& client_kx,
                                const KxPublicKey& server_kx, std::string_view cookie_hex);
// The server's side: the fingerprint of an identity whose box opens and whose signature
// verifies over this handshake; nullopt for anything else.
std::optional<std::string> open_hello_identity(const SessionKeys& server_keys, const KxPublicKey& client_kx,
                                               const KxPublicKey& server_kx, std::string_view cookie_hex,
                                               std::string_view sealed_hex);

// The identity file's text: one line "fts-identity-1 <64 hex digits of the seed>".
std::string identity_file_text(const Identity& id);
std::optional<Identity> parse_identity_file(std::string_view text);

}  // namespace fts::protocol
