// The fixed 21-byte binary header in front of every datagram (big-endian):
//   0  u32 protocol id "FTSP"     4  u16 version      6  u8 flags (bits 0-1: encoding)
//   7  u32 session id (0 before the handshake completes)
//  11  u16 sequence   13  u16 ack (latest sequence received)   15  u32 ack bits
//  19  u16 ack delay (ms the packet `ack` waited at the sender before this one left)
// The first 19 bytes (the "prefix") are the same in every protocol version, and a
// version refusal is written as the prefix alone followed by a JSON payload, so that a
// client of any version can read it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fts/protocol/constants.hpp"
#include "fts/protocol/decoded.hpp"

namespace fts::protocol {

inline constexpr std::size_t kHeaderPrefixBytes = 19;
inline constexpr std::size_t kHeaderBytes = 21;
// A sealed datagram (every one after the handshake, PROTOCOL.md 5.7) carries this many
// more bytes: the Poly1305 tag after the encrypted payload.
inline constexpr std::size_t kSealTagBytes = 16;

struct Header {
  std::uint16_t version = kProtocolVersion;
  Encoding encoding = Encoding::msgpack;
  std::uint32_t session = 0;
  std::uint16_t sequence = 0;
  std::uint16_t ack = 0;
  std::uint32_t ack_bits = 0;  // bit i set: sequence (ack - 1 - i) was received too
  std::uint16_t ack_delay_ms = 0;  // how long `ack` waited here before this packet left

  bool operator==(const Header&) const = default;
};

// Appends the 21 header bytes to `out`.
void write_header(const Header& header, std::vector<std::uint8_t>& out);
// Appends only the 19-byte prefix (version refusals, section 5.5 of PROTOCOL.md).
void write_header_prefix(const Header& header, std::vector<std::uint8_t>& out);

// Reads the header, checking protocol id, length limits and flags. A version other than
// `expected_version` is rejected with Reject::bad_version (the header is still readable
// with read_header_any_version, to answer with a clear error).
Decoded<Header> read_header(std::span<const std::uint8_t> bytes,
                            std::uint16_t expected_version = kProtocolVersion);
// Reads the version-independent 19-byte prefix only (ack_delay_ms stays 0).
Decoded<Header> read_header_any_version(std::span<const std::uint8_t> bytes);

// 16-bit sequence arithmetic with wrap-around: is `a` newer than `b`?
inline bool sequence_newer(std::uint16_t a, std::uint16_t b) {
  return a != b && static_cast<std::uint16_t>(a - b) < 0x8000u;
}

}  // namespace fts::protocol
