// The frames of the hand-over channel between servers (issue 42, PROTOCOL.md 14), pure:
// the key from the fleet secret, a frame's bytes and its check. The sockets are
// net/handover.cpp's.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fts::server::handover {

using Bytes = std::vector<std::uint8_t>;

inline constexpr std::string_view kMagic = "FTSHOV01";  // the peer's first 8 bytes
inline constexpr std::size_t kChallengeBytes = 32;
inline constexpr std::size_t kMacBytes = 32;             // HMAC-SHA-256
inline constexpr std::uint32_t kMaxFrameBytes = 64u << 20;
inline constexpr std::size_t kSecretMinBytes = 32;
inline constexpr int kFormat = 1;                        // the request's "fts_handover"
inline constexpr std::string_view kRequestLabel = "fts-handover-1 request";
inline constexpr std::string_view kReplyLabel = "fts-handover-1 reply";
inline constexpr std::string_view kConfirmLabel = "fts-handover-1 confirm";

// The channel's key: BLAKE2b-256 (crypto_generichash) of the secret's bytes.
std::string key_of_secret(std::string_view secret);
// The fleet secret's file -> its key; "" with `why` set when it cannot be read, is shorter
// than kSecretMinBytes or is readable by others than its owner.
std::string read_secret_file(const std::string& path, std::string& why);

// HMAC-SHA-256 under `key` of label || challenge || json.
std::array<std::uint8_t, kMacBytes> mac(const std::string& key, std::string_view label, const Bytes& challenge,
                                        std::string_view json);
// A frame: the JSON's length (4 bytes, big-endian), the JSON, its MAC.
Bytes frame(const std::string& key, std::string_view label, const Bytes& challenge, std::string_view json);
// A frame's length from its first 4 bytes.
std::uint32_t frame_length(const std::array<std::uint8_t, 4>& head);
// A frame's body (JSON then MAC) -> the JSON, when the MAC is the key's.
std::optional<std::string> open_body(const std::string& key, std::string_view label, const Bytes& challenge,
                                     const Bytes& body);

}  // namespace fts::server::handover
