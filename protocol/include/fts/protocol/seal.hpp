// Sealed packets (PROTOCOL.md 5.7): after the handshake every datagram, in both
// directions, is the 21-byte header in clear followed by its payload encrypted and
// authenticated with ChaCha20-Poly1305-IETF (libsodium), keyed per session and direction
// by a crypto_kx key exchange made during the handshake. The header is the associated
// data; the nonce is the direction and the packet's 64-bit extended sequence. A replay
// window refuses a sequence seen before or too old. A payload is parsed only after its
// tag verified (open_sealed).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fts/protocol/codec.hpp"
#include "fts/protocol/decoded.hpp"
#include "fts/protocol/header.hpp"

namespace fts::protocol {

inline constexpr std::size_t kKxKeyBytes = 32;
inline constexpr std::size_t kSessionKeyBytes = 32;
inline constexpr std::size_t kSealNonceBytes = 12;

using KxPublicKey = std::array<std::uint8_t, kKxKeyBytes>;
using SessionKey = std::array<std::uint8_t, kSessionKeyBytes>;
using SealNonce = std::array<std::uint8_t, kSealNonceBytes>;

struct KxKeyPair {
  KxPublicKey public_key{};
  std::array<std::uint8_t, kKxKeyBytes> secret_key{};
};

// crypto_kx_seed_keypair (deterministic: servers derive theirs from the server key) and
// crypto_kx_keypair (random: a client makes a new one for every connection attempt).
KxKeyPair kx_keypair_from_seed(const std::array<std::uint8_t, 32>& seed);
KxKeyPair kx_random_keypair();

// rx: what this side opens with, tx: what it seals with. The client's tx is the
// server's rx and the other way round.
struct SessionKeys {
  SessionKey rx{};
  SessionKey tx{};
};
// nullopt for a peer key libsodium refuses (a low-order point).
std::optional<SessionKeys> client_session_keys(const KxKeyPair& client, const KxPublicKey& server);
std::optional<SessionKeys> server_session_keys(const KxKeyPair& server, const KxPublicKey& client);

// The first nonce byte: who sealed it. The hello's token box has its own.
enum class SealDirection : std::uint8_t { client_to_server = 1, server_to_client = 2, hello_token = 3, hello_identity = 4 };

// byte 0: direction, bytes 1-3: zero, bytes 4-11: the extended sequence, big-endian.
SealNonce seal_nonce(SealDirection direction, std::uint64_t sequence);

// ChaCha20-Poly1305-IETF, combined mode: appends ciphertext and the 16-byte tag to `out`.
void aead_seal(const SessionKey& key, const SealNonce& nonce, std::span<const std::uint8_t> ad,
               std::span<const std::uint8_t> plain, std::vector<std::uint8_t>& out);
// Replaces `plain` with the opened text; false (plain unspecified) if the tag is wrong.
bool aead_open(const SessionKey& key, const SealNonce& nonce, std::span<const std::uint8_t> ad,
               std::span<const std::uint8_t> sealed, std::vector<std::uint8_t>& plain);

// The hello's sealed token (PROTOCOL.md 5.7.3): 96 hex digits of the 32 token characters
// sealed with the client's tx key, nonce (hello_token, 0), the client's kx public key as
// associated data. "" opens to nullopt as does anything forged.
std::string seal_hello_token(const SessionKeys& client_keys, const KxPublicKey& client_public,
                             std::string_view token);
std::optional<std::string> open_hello_token(const SessionKeys& server_keys, const KxPublicKey& client_public,
                                            std::string_view sealed_hex);

// 64 hex digits <-> a public key (nullopt for anything else).
std::optional<KxPublicKey> parse_public_key(std::string_view hex);
std::string public_key_hex(const KxPublicKey& key);

// Rebuilds the 64-bit sequence from the 16 bits in a header: the value with these low
// bits nearest to `newest` (the highest sequence accepted so far). The sender's side
// counts a wrap of its 16-bit sequence (65535 -> 1) as one more 65536.
std::uint64_t extend_sequence(std::uint16_t wire, std::uint64_t newest);

// Why a sealed datagram was dropped, counted per session.
struct SealDrops {
  std::uint64_t forged = 0;    // the tag did not verify (forged, tampered or wrong key)
  std::uint64_t replayed = 0;  // a sequence seen already, or older than the window
  std::uint64_t total() const { return forged + replayed; }
};

// One side's keys and sequence state for a session.
class SealedChannel {
 public:
  static constexpr std::uint64_t kReplayWindow = 64;

  SealedChannel() = default;
  SealedChannel(const SessionKeys& keys, SealDirection outgoing, SealDirection incoming)
      : keys_(keys), out_(outgoing), in_(incoming), ready_(true) {}
  bool ready() const { return ready_; }

  // Header (as written by write_header) + the sealed payload, appended to `out`. The
  // header's sequence must be the next one of this side (AckWindow::stamp).
  void seal(const Header& header, std::span<const std::uint8_t> payload, std::vector<std::uint8_t>& out);
  // Opens a datagram whose 21-byte header is `header` (already read): the plaintext
  // payload goes to `plain`. Rejects (and counts) a replayed sequence before any
  // crypto, then a wrong tag; only a datagram that verifies moves the replay window.
  std::optional<Reject> open(const Header& header, std::span<const std::uint8_t> datagram,
                             std::vector<std::uint8_t>& plain);

  const SealDrops& drops() const { return drops_; }

 private:
  SessionKeys keys_{};
  SealDirection out_ = SealDirection::client_to_server;
  SealDirection in_ = SealDirection::server_to_client;
  bool ready_ = false;
  std::uint64_t sent_epoch_ = 0;   // wraps of our 16-bit sequence
  std::uint16_t last_sent_ = 0;
  bool received_any_ = false;
  std::uint64_t newest_ = 0;       // highest extended sequence opened
  std::uint64_t seen_bits_ = 0;    // bit i: newest_ - i was opened (bit 0 is newest_)
  SealDrops drops_;
};

// The messages encoded in the header's encoding, sealed: a whole datagram.
std::vector<std::uint8_t> encode_sealed(SealedChannel& channel, const Header& header,
                                        const std::vector<Message>& messages);
// Reads the full header, opens the datagram (replay window, tag) and only then decodes
// the payload. `plain` is a scratch buffer the caller reuses.
Decoded<Datagram> open_sealed(SealedChannel& channel, std::span<const std::uint8_t> bytes,
                              std::uint16_t expected_version, std::vector<std::uint8_t>& plain);

}  // namespace fts::protocol
