// Stateless handshake cookies and session secrets, keyed with a server key made at
// start-up (libsodium's keyed BLAKE2b, crypto_generichash). The key is passed in, so
// tests are deterministic; a server makes it with random_key().
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace fts::protocol {

using ServerKey = std::array<std::uint8_t, 32>;

// 32 bytes from libsodium's system random generator.
ServerKey random_key();

// 48 hex digits: the 8-byte issue time (ms, big-endian) then a 16-byte keyed hash of
// ("cookie", issue time, address). Nothing is stored: the server recomputes it.
std::string make_cookie(const ServerKey& key, std::string_view address, std::uint64_t now_ms);

enum class CookieCheck { ok, forged, expired };

// A cookie is good for `lifetime_ms` after issue, only from the address it was issued to.
CookieCheck check_cookie(const ServerKey& key, std::string_view address, std::string_view cookie,
                         std::uint64_t now_ms, std::uint64_t lifetime_ms);

// Secrets of the n-th session a server makes: a 32-hex-digit reconnect token and a
// non-zero 32-bit session id, unguessable without the key, deterministic with it.
std::string derive_token(const ServerKey& key, std::uint64_t n);
std::uint32_t derive_session_id(const ServerKey& key, std::uint64_t n);

// What verifies a reconnect token without holding it (a journal stores this, never the
// token): 32 hex digits of an unkeyed BLAKE2b of the token. Tokens are 128 random-looking
// bits, so the verifier cannot be turned back into one.
std::string token_verifier(std::string_view token);

// The seed of the server's key-exchange key pair (PROTOCOL.md 5.7): fixed for a server
// key, so that tests are deterministic.
std::array<std::uint8_t, 32> derive_kx_seed(const ServerKey& key);

// Lower-case hex of bytes.
std::string to_hex(const std::uint8_t* data, std::size_t size);
// Lower-case hex of exactly out.size() bytes into `out`; false for anything else.
bool from_hex(std::string_view hex, std::span<std::uint8_t> out);
// Initialises libsodium once (the cookies here and the seal, seal.hpp, call it first).
void ensure_sodium();

}  // namespace fts::protocol
