// Wire constants shared by every part of the protocol (see protocol/PROTOCOL.md).
#pragma once

#include <cstddef>
#include <cstdint>

namespace fts::protocol {

// "FTSP" read as a big-endian 32-bit integer: the first four bytes of every datagram.
inline constexpr std::uint32_t kProtocolId = 0x46545350u;
inline constexpr std::uint16_t kProtocolVersion = 3;

// No datagram, in either direction, is ever larger than this.
inline constexpr std::size_t kMaxDatagramBytes = 1200;
// A hello datagram must be at least this large (padding), so that no reply sent before
// the handshake completes is larger than the request that caused it.
inline constexpr std::size_t kMinHelloBytes = 512;

// Quantization of positions, velocities, radii and masses in snapshots: 1/16 unit.
inline constexpr double kQuantaPerUnit = 16.0;

// Hard limits a decoder enforces (anything beyond is out of range).
inline constexpr std::size_t kMaxMessagesPerDatagram = 32;
inline constexpr std::size_t kMaxNameBytes = 16;
inline constexpr std::size_t kMaxTextBytes = 200;
inline constexpr std::size_t kMaxInputFrames = 16;
inline constexpr std::size_t kMaxBallsPerMessage = 256;
inline constexpr std::size_t kMaxPlayersPerMessage = 64;
inline constexpr std::size_t kMaxEventsPerMessage = 64;
inline constexpr std::size_t kBoardRows = 10;  // rows of a leaderboard (PROTOCOL.md 4.7c)
inline constexpr std::uint32_t kMaxSnapshotParts = 16;
inline constexpr std::int64_t kMaxCoins = 1'000'000'000'000'000;  // 10^15
inline constexpr std::int64_t kMaxQuantized = std::int64_t{1} << 40;
// Snapshot deltas predict motion entries from the base's velocity (PROTOCOL.md 8.2):
// the tick rate a snap states, and the most ticks a prediction spans.
inline constexpr std::uint32_t kMaxTickRateHz = 10000;
inline constexpr std::uint32_t kMaxPredictionTicks = 1u << 20;
// Payload shape, checked while parsing (both encodings): arrays and objects nested at
// most this deep (a snapshot needs 5), and at most this many values in all (a value
// takes at least one byte, so a datagram cannot hold more).
inline constexpr std::size_t kMaxNestingDepth = 6;
inline constexpr std::size_t kMaxPayloadValues = kMaxDatagramBytes;

// The two payload encodings; the client picks one at connect, the header names it.
enum class Encoding : std::uint8_t { json = 0, msgpack = 1 };

// The reason of a bye that ends a health-check session: the server frees the player's
// slot at once instead of holding it for the reconnect window.
inline constexpr const char* kProbeByeReason = "probe";

}  // namespace fts::protocol
