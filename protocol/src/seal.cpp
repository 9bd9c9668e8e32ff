#include "fts/protocol/seal.hpp"

#include <sodium.h>

#include <cstring>

#include "fts/protocol/cookie.hpp"

namespace fts::protocol {
namespace {

static_assert(crypto_kx_PUBLICKEYBYTES == kKxKeyBytes && crypto_kx_SECRETKEYBYTES == kKxKeyBytes);
static_assert(crypto_kx_SEEDBYTES == 32 && crypto_kx_SESSIONKEYBYTES == kSessionKeyBytes);
static_assert(crypto_aead_chacha20poly1305_ietf_KEYBYTES == kSessionKeyBytes);
static_assert(crypto_aead_chacha20poly1305_ietf_NPUBBYTES == kSealNonceBytes);
static_assert(crypto_aead_chacha20poly1305_ietf_ABYTES == kSealTagBytes);

constexpr std::size_t kTokenChars = 32;

}  // namespace

KxKeyPair kx_keypair_from_seed(const std::array<std::uint8_t, 32>& seed) {
  ensure_sodium();
  KxKeyPair k;
  crypto_kx_seed_keypair(k.public_key.data(), k.secret_key.data(), seed.data());
  return k;
}

KxKeyPair kx_random_keypair() {
  ensure_sodium();
  KxKeyPair k;
  crypto_kx_keypair(k.public_key.data(), k.secret_key.data());
  return k;
}

namespace {

// crypto_kx_client_session_keys and crypto_kx_server_session_keys have one signature.
using KxDerive = int (*)(unsigned char*, unsigned char*, const unsigned char*, const unsigned char*,
                         const unsigned char*);

std::optional<SessionKeys> derive_session_keys(KxDerive derive, const KxKeyPair& own, const KxPublicKey& peer) {
  ensure_sodium();
  SessionKeys k;
  if (derive(k.rx.data(), k.tx.data(), own.public_key.data(), own.secret_key.data(), peer.data()) != 0)
    return std::nullopt;
  return k;
}

}  // namespace

std::optional<SessionKeys> client_session_keys(const KxKeyPair& client, const KxPublicKey& server) {
  return derive_session_keys(crypto_kx_client_session_keys, client, server);
}

std::optional<SessionKeys> server_session_keys(const KxKeyPair& server, const KxPublicKey& client) {
  return derive_session_keys(crypto_kx_server_session_keys, server, client);
}

SealNonce seal_nonce(SealDirection direction, std::uint64_t sequence) {
  SealNonce n{};
  n[0] = static_cast<std::uint8_t>(direction);
  for (int i = 0; i < 8; ++i) n[4 + i] = static_cast<std::uint8_t>(sequence >> (8 * (7 - i)));
  return n;
}

void aead_seal(const SessionKey& key, const SealNonce& nonce, std::span<const std::uint8_t> ad,
               std::span<const std::uint8_t> plain, std::vector<std::uint8_t>& out) {
  const std::size_t at = out.size();
  out.resize(at + plain.size() + kSealTagBytes);
  unsigned long long written = 0;
  crypto_aead_chacha20poly1305_ietf_encrypt(out.data() + at, &written, plain.data(), plain.size(), ad.data(),
                                            ad.size(), nullptr, nonce.data(), key.data());
  out.resize(at + static_cast<std::size_t>(written));
}

bool aead_open(const SessionKey& key, const SealNonce& nonce, std::span<const std::uint8_t> ad,
               std::span<const std::uint8_t> sealed, std::vector<std::uint8_t>& plain) {
  if (sealed.size() < kSealTagBytes) return false;
  plain.resize(sealed.size() - kSealTagBytes);
  unsigned long long written = 0;
  if (crypto_aead_chacha20poly1305_ietf_decrypt(plain.data(), &written, nullptr, sealed.data(), sealed.size(),
                                                ad.data(), ad.size(), nonce.data(), key.data()) != 0)
    return false;
  plain.resize(static_cast<std::size_t>(written));
  return true;
}

std::optional<KxPublicKey> parse_public_key(std::string_view hex) {
  KxPublicKey k{};
  if (!from_hex(hex, k)) return std::nullopt;
  return k;
}

std::string public_key_hex(const KxPublicKey& key) { return to_hex(key.data(), key.size()); }

std::string seal_hello_token(const SessionKeys& client_keys, const KxPublicKey& client_public,
                             std::string_view token) {
  if (token.size() != kTokenChars) return {};
  std::vector<std::uint8_t> sealed;
  aead_seal(client_keys.tx, seal_nonce(SealDirection::hello_token, 0), client_public,
            {reinterpret_cast<const std::uint8_t*>(token.data()), token.size()}, sealed);
  return to_hex(sealed.data(), sealed.size());
}

std::optional<std::string> open_hello_token(const SessionKeys& server_keys, const KxPublicKey& client_public,
                                            std::string_view sealed_hex) {
  std::array<std::uint8_t, kTokenChars + kSealTagBytes> sealed{};
  if (!from_hex(sealed_hex, sealed)) return std::nullopt;
  std::vector<std::uint8_t> plain;
  if (!aead_open(server_keys.rx, seal_nonce(SealDirection::hello_token, 0), client_public, sealed, plain))
    return std::nullopt;
  return std::string(plain.begin(), plain.end());
}

std::uint64_t extend_sequence(std::uint16_t wire, std::uint64_t newest) {
  constexpr std::uint64_t kSpan = 0x10000;
  std::uint64_t candidate = (newest & ~(kSpan - 1)) | wire;
  if (candidate > newest + kSpan / 2 && candidate >= kSpan) candidate -= kSpan;
  else if (candidate + kSpan / 2 < newest) candidate += kSpan;
  return candidate;
}

void SealedChannel::seal(const Header& header, std::span<const std::uint8_t> payload,
                         std::vector<std::uint8_t>& out) {
  if (last_sent_ != 0 && header.sequence <= last_sent_) ++sent_epoch_;
  last_sent_ = header.sequence;
  const std::uint64_t sequence = (sent_epoch_ << 16) | header.sequence;
  const std::size_t at = out.size();
  write_header(header, out);
  const std::array<std::uint8_t, kHeaderBytes> ad = [&] {
    std::array<std::uint8_t, kHeaderBytes> a{};
    std::memcpy(a.data(), out.data() + at, kHeaderBytes);
    return a;
  }();
  aead_seal(keys_.tx, seal_nonce(out_, sequence), ad, payload, out);
}

std::optional<Reject> SealedChannel::open(const Header& header, std::span<const std::uint8_t> datagram,
                                          std::vector<std::uint8_t>& plain) {
  // Too short to hold a tag: cut short, not a forgery (no tag was checked).
  if (datagram.size() < kHeaderBytes + kSealTagBytes) return Reject::truncated;
  if (!ready_) {
    ++drops_.forged;
    return Reject::forged;
  }
  const std::uint64_t sequence = received_any_ ? extend_sequence(header.sequence, newest_) : header.sequence;
  if (received_any_ && sequence <= newest_) {
    const std::uint64_t behind = newest_ - sequence;
    if (behind >= kReplayWindow || (seen_bits_ >> behind) & 1u) {
      ++drops_.replayed;
      return Reject::replayed;
    }
  }
  if (!aead_open(keys_.rx, seal_nonce(in_, sequence), datagram.first(kHeaderBytes), datagram.subspan(kHeaderBytes),
                 plain)) {
    ++drops_.forged;
    return Reject::forged;
  }
  if (!received_any_ || sequence > newest_) {
    const std::uint64_t shift = received_any_ ? sequence - newest_ : kReplayWindow;
    seen_bits_ = (shift >= kReplayWindow ? 0 : seen_bits_ << shift) | 1u;
    newest_ = sequence;
    received_any_ = true;
  } else {
    seen_bits_ |= std::uint64_t{1} << (newest_ - sequence);
  }
  return std::nullopt;
}

std::vector<std::uint8_t> encode_sealed(SealedChannel& channel, const Header& header,
                                        const std::vector<Message>& messages) {
  std::vector<std::uint8_t> payload;
  append_payload(header.encoding, messages, payload);
  std::vector<std::uint8_t> out;
  out.reserve(kHeaderBytes + payload.size() + kSealTagBytes);
  channel.seal(header, payload, out);
  return out;
}

Decoded<Datagram> open_sealed(SealedChannel& channel, std::span<const std::uint8_t> bytes,
                              std::uint16_t expected_version, std::vector<std::uint8_t>& plain) {
  auto header = read_header(bytes, expected_version);
  if (!header) return header.error();
  if (auto why = channel.open(*header, bytes, plain)) return *why;
  auto messages = decode_payload(header->encoding, plain);
  if (!messages) return messages.error();
  return Datagram{*header, std::move(*messages)};
}

}  // namespace fts::protocol
