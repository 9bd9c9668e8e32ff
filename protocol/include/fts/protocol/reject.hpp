// Why an incoming datagram or message was dropped. Every drop is counted, none throws.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fts/protocol/code_table.hpp"

namespace fts::protocol {

enum class Reject : std::uint8_t {
  truncated, oversize, wrong_protocol_id, bad_version, bad_flags, garbage, unknown_type, out_of_range,
  unpadded_hello, bad_cookie, bad_token, unknown_session, address_mismatch, unexpected, server_full,
  unknown_base, stale, rate_limited, overflow, address_full, idle, join_refused, forged, replayed, bad_key,
  takeover_limited, bad_field, unknown_room, code_limited, bad_identity, count_
};

inline constexpr std::size_t kRejectCount = static_cast<std::size_t>(Reject::count_);

// Each reason once, with what it means as PROTOCOL.md section 11 says it (a test holds
// the document to this table).
inline constexpr std::array<CodeRow<Reject>, kRejectCount> kRejects{{
    {Reject::truncated, "truncated",
     "shorter than the header, an empty payload, or a sealed datagram shorter than its header and tag (21 + 16 "
     "bytes, 5.7.2)"},
    {Reject::oversize, "oversize", "longer than 1200 bytes"},
    {Reject::wrong_protocol_id, "wrong_protocol_id", "does not start with `FTSP`"},
    {Reject::bad_version, "bad_version", "another protocol version (a hello-sized one gets an `error`, 5.5)"},
    {Reject::bad_flags, "bad_flags",
     "unknown encoding or reserved bits set (a hello-sized one of session 0 gets `bad_hello`, 4.1)"},
    {Reject::garbage, "garbage", "payload does not parse, or a field is missing or has the wrong type"},
    {Reject::unknown_type, "unknown_type", "a message type this version does not know"},
    {Reject::out_of_range, "out_of_range", "a value outside its documented range"},
    {Reject::unpadded_hello, "unpadded_hello", "hello datagram under 512 bytes"},
    {Reject::bad_cookie, "bad_cookie", "cookie forged, for another address, or expired"},
    {Reject::bad_token, "bad_token", "reconnect token unknown or expired"},
    {Reject::unknown_session, "unknown_session", "session id unknown or no longer live"},
    {Reject::address_mismatch, "address_mismatch", "a live session used from another address"},
    {Reject::unexpected, "unexpected",
     "a valid message that makes no sense here (e.g. a `welcome` sent to the server, or a `ping` without a "
     "session)"},
    {Reject::server_full, "server_full", "no free player slot"},
    {Reject::unknown_base, "unknown_base", "snapshot delta against a snapshot the client does not have"},
    {Reject::stale, "stale",
     "a packet that opened but is more than 32 behind the newest (the ack bits' reach), already delivered "
     "reliable message, old snapshot part (a duplicated sealed datagram is `replayed`)"},
    {Reject::rate_limited, "rate_limited", "over the host's or the session's datagram rate (10.1)"},
    {Reject::overflow, "overflow", "a session over a queue bound (10.1); counted once, the session is dropped"},
    {Reject::address_full, "address_full", "a new player from a host with 4 seated sessions (10.1)"},
    {Reject::idle, "idle", "a session dropped for 120 s without real input (10.1)"},
    {Reject::join_refused, "join_refused",
     "a new player's room choice refused: `room_full`, `server_full`, `bad_join`, `draining`, or "
     "`address_full` for a new room from a host at its room cap (5.6, 10.1)"},
    {Reject::forged, "forged",
     "a sealed datagram whose tag does not verify: forged, tampered, cut short or sealed with other keys (5.7.2)"},
    {Reject::replayed, "replayed",
     "a sealed datagram whose sequence was opened already or is 64 or more behind the newest (5.7.2)"},
    {Reject::bad_key, "bad_key",
     "a cookie hello without a usable `key` (5.7.1); a challenge whose `key` the client cannot use"},
    {Reject::takeover_limited, "takeover_limited", "a token hello over its host's rate (5.4, 10.1)"},
    {Reject::bad_field, "bad_field",
     "a `cmd` field that does not read (4.6): the command is answered (`op`, `item` or `field`) and not "
     "applied; nothing else of the datagram is dropped"},
    {Reject::unknown_room, "unknown_room", "a `join`/`spectate` naming no open room, refused `no_such_room` (5.6)"},
    {Reject::code_limited, "code_limited",
     "a `join`/`spectate` over its host's rate of unknown room codes, refused `rate_limited` (10.1)"},
    {Reject::bad_identity, "bad_identity",
     "a cookie hello whose `id` box does not open or whose signature does not verify, refused `bad_identity` (5.8)"},
}};
static_assert(rows_in_order(kRejects), "kRejects: one row per Reject, in order");

// Stable lower-case name, as used in logs and stats ("truncated", "bad_cookie", ...).
constexpr std::string_view to_string(Reject reason) { return name_in(kRejects, reason); }

// Drops counted by reason.
struct RejectCounters {
  std::array<std::uint64_t, kRejectCount> counts{};

  void add(Reject reason) { ++counts[static_cast<std::size_t>(reason)]; }
  void add(const RejectCounters& more) {
    for (std::size_t i = 0; i < counts.size(); ++i) counts[i] += more.counts[i];
  }
  std::uint64_t operator[](Reject reason) const { return counts[static_cast<std::size_t>(reason)]; }
  std::uint64_t total() const {
    std::uint64_t sum = 0;
    for (auto c : counts) sum += c;
    return sum;
  }
};

}  // namespace fts::protocol
