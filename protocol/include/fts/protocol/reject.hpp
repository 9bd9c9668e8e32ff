// Why an incoming datagram or message was dropped. Every drop is counted, none throws.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace fts::protocol {

enum class Reject : std::uint8_t {
  truncated,          // shorter than the header, or a message cut short
  oversize,           // longer than kMaxDatagramBytes
  wrong_protocol_id,  // first four bytes are not "FTSP"
  bad_version,        // another protocol version
  bad_flags,          // unknown encoding or reserved header bits set
  garbage,            // payload does not parse, or fields have the wrong shape
  unknown_type,       // a message type this version does not know
  out_of_range,       // a field value outside its documented range
  unpadded_hello,     // hello datagram smaller than kMinHelloBytes
  bad_cookie,         // handshake cookie forged, for another address, or expired
  bad_token,          // reconnect token unknown or expired
  unknown_session,    // session id not (or no longer) known
  address_mismatch,   // a live session used from another address
  unexpected,         // valid message that makes no sense in the current state
  server_full,        // no free player slot
  unknown_base,       // snapshot delta against a snapshot we do not have
  stale,              // older than what we already have (sequence or snapshot tick)
  rate_limited,       // over the session's or the address's datagram rate
  overflow,           // a session over a queue cap: the session is dropped (error "overflow")
  address_full,       // a new session from a host that has max_sessions_per_address already
  idle,               // a session without real input for idle_timeout_ms: dropped (error "idle")
  join_refused,       // a new player's room choice refused (room_full, server_full, bad_join, draining)
  forged,             // a sealed datagram whose tag does not verify (forged, tampered, wrong key)
  replayed,           // a sealed datagram whose sequence was seen already or is older than the window
  bad_key,            // a handshake key exchange public key missing or refused
  takeover_limited,   // over the address's rate of token take-overs
  bad_field,          // a cmd field that did not read: the cmd is answered, not applied; the datagram goes on
  unknown_room,       // a join or spectate naming no open room (refused no_such_room)
  code_limited,       // a join or spectate over its host's rate of unknown room codes (refused rate_limited)
  count_
};

inline constexpr std::size_t kRejectCount = static_cast<std::size_t>(Reject::count_);

// Stable lower-case name, as used in logs and stats ("truncated", "bad_cookie", ...).
std::string_view to_string(Reject reason);

// Drops counted by reason.
struct RejectCounters {
  std::array<std::uint64_t, kRejectCount> counts{};

  void add(Reject reason) { ++counts[static_cast<std::size_t>(reason)]; }
  std::uint64_t operator[](Reject reason) const { return counts[static_cast<std::size_t>(reason)]; }
  std::uint64_t total() const {
    std::uint64_t sum = 0;
    for (auto c : counts) sum += c;
    return sum;
  }
};

}  // namespace fts::protocol
