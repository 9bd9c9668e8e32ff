// Every code an `error` (PROTOCOL.md 4.4) and a `result` (4.7) carries, once, with its
// meaning as the document states it. The server sends these constants, the client maps
// them to text; no layer spells a code itself. The drop reasons are reject.hpp's.
#pragma once

#include <cstdint>
#include <string>

#include "fts/protocol/code_table.hpp"
#include "fts/protocol/messages.hpp"

namespace fts::protocol {

enum class ErrorCode : std::uint8_t {
  version, bad_hello, bad_name, bad_key, bad_token, rate_limited, server_full, room_full, no_such_room,
  bad_join, address_full, draining, refused, taken_over, overflow, idle, kicked, banned, room_closed,
  shutdown, timeout, bye, bad_identity, count_
};

inline constexpr std::array<CodeRow<ErrorCode>, static_cast<std::size_t>(ErrorCode::count_)> kErrorCodes{{
    {ErrorCode::version, "version",
     "a hello-sized datagram of another protocol version; the answer is the header prefix and a JSON payload (5.5)"},
    {ErrorCode::bad_hello, "bad_hello",
     "a hello-sized datagram (at least 512 bytes, session 0, `FTSP` and the server's version) that does not "
     "decode; `msg` names the drop reason (4.1)"},
    {ErrorCode::bad_name, "bad_name", "the hello's `name` is not 1..16 printable ASCII characters; `msg` says why (4.1)"},
    {ErrorCode::bad_key, "bad_key", "a hello with a cookie whose `key` is absent, `\"\"` or refused by `crypto_kx` (5.7.1)"},
    {ErrorCode::bad_token, "bad_token",
     "the hello's token is unknown, expired, or a sealed box that does not open (5.4, 5.7.3); connect again "
     "without it"},
    {ErrorCode::rate_limited, "rate_limited",
     "a token hello over its host's rate (5.4), or a `join`/`spectate` over its host's rate of unknown room "
     "codes (5.6, 10.1)"},
    {ErrorCode::server_full, "server_full",
     "no place for a new player: every seat or session slot is taken, a new room is needed and `--max-rooms` "
     "are open, or the server is draining (5.5, 5.6)"},
    {ErrorCode::room_full, "room_full",
     "`join` of a room whose seats are taken (held seats count), `spectate` of a room at its spectator cap, "
     "or a token hello of a player who quit into a room that filled up since (5.4, 5.6)"},
    {ErrorCode::no_such_room, "no_such_room",
     "`join`/`spectate` of a code that is not an open room, or not a code at all (5.6)"},
    {ErrorCode::bad_join, "bad_join", "`join` is none of `quick`, `create`, `join`, `spectate` (5.6)"},
    {ErrorCode::address_full, "address_full",
     "a new player from a host with 4 seated sessions, or a new spectator from a host with 8 spectators "
     "(5.5, 10.1), or a new room asked for by a host that made 4 rooms still open (5.6, 10.1)"},
    {ErrorCode::draining, "draining",
     "the server is draining for a shutdown: a new player is turned away, a reconnect still resumes"},
    {ErrorCode::refused, "refused",
     "a new player turned away without another code: the host named none, or the room's match refused the join"},
    {ErrorCode::taken_over, "taken_over",
     "sent on the old session: a token hello from another address took the player over (5.4)"},
    {ErrorCode::overflow, "overflow", "the session went over a queue bound (10.1): it is closed"},
    {ErrorCode::idle, "idle",
     "no real input for `idle_timeout_ms` (120 s): the seat is freed, the progress kept (6, 10.1)"},
    {ErrorCode::kicked, "kicked", "the host kicked the player; `msg` gives the host's reason"},
    {ErrorCode::banned, "banned", "the host banned the address: its datagrams are then dropped unanswered"},
    {ErrorCode::room_closed, "room_closed", "the room was closed: empty for `--room-idle-ms`, or by the host (5.6)"},
    {ErrorCode::shutdown, "shutdown", "the server is shutting down"},
    {ErrorCode::timeout, "timeout",
     "the C++ client's own: no answer during the handshake, or the server stopped answering", false},
    {ErrorCode::bye, "bye", "the C++ client's own: the server sent `bye` (the message is its reason)", false},
    {ErrorCode::bad_identity, "bad_identity",
     "the hello's `id` does not open or its signature does not verify over this handshake (5.8); connect "
     "again (a new attempt signs anew), or as a guest"},
}};
static_assert(rows_in_order(kErrorCodes), "kErrorCodes: one row per ErrorCode, in order");

// The codes of a command's result. ok is the only one with `ok: true`.
enum class ResultCode : std::uint8_t {
  ok, coins, owned, phase, dead, item, op, field, spectator, rate, empty, busy, no_profiles, unavailable, guest, count_
};

inline constexpr std::array<CodeRow<ResultCode>, static_cast<std::size_t>(ResultCode::count_)> kResultCodes{{
    {ResultCode::ok, "ok", "applied (`ok: true`); for `rooms`, `msg` is the room list (5.6)"},
    {ResultCode::coins, "coins", "not enough coins for the item"},
    {ResultCode::owned, "owned", "an item bought once (rockets, bank) that the player has"},
    {ResultCode::phase, "phase", "not now: the phase does not allow the command (the shop is closed)"},
    {ResultCode::dead, "dead", "the player is out of the match"},
    {ResultCode::item, "item", "a `buy` whose `item` is missing or no shop item, or any command whose `item` does not read (4.6)"},
    {ResultCode::op, "op", "an `op` this server does not know, or one that does not read (4.6)"},
    {ResultCode::field, "field", "another field that does not read (4.6)"},
    {ResultCode::spectator, "spectator", "a spectator's command other than `rooms` (5.6)"},
    {ResultCode::rate, "rate", "a chat line over the chat rate (4.6)"},
    {ResultCode::empty, "empty", "a chat line with nothing printable left (4.6)"},
    {ResultCode::busy, "busy",
     "a `top` or `forget` while the player's previous one is unanswered, or within a second of it (4.7c)"},
    {ResultCode::no_profiles, "no_profiles", "a `top` or `forget` on a server that keeps no profiles (4.7c)"},
    {ResultCode::unavailable, "unavailable",
     "a `top` while the profile database does not answer, or a `forget` the server could not queue (4.7c)"},
    {ResultCode::guest, "guest", "a `forget` in a session without a proven identity: there is no profile (4.7c, 5.8)"},
}};
static_assert(rows_in_order(kResultCodes), "kResultCodes: one row per ResultCode, in order");

// The sentence a player reads for a result that needs no context: the server sends it as
// the result's message and the client shows it for the code, one string. "" where the
// words depend on the item, the player or the server (the client's own, or the message).
constexpr std::string_view result_sentence(ResultCode c) {
  switch (c) {
    case ResultCode::rate: return "too many chat lines: wait a moment";
    case ResultCode::empty: return "nothing to say";
    case ResultCode::busy: return "asked too often: wait a moment";
    case ResultCode::no_profiles: return "this server keeps no profiles";
    case ResultCode::unavailable: return "the server's profile database is not available now: try again later";
    case ResultCode::guest: return "you play as a guest: there is no profile to erase";
    case ResultCode::ok:
    case ResultCode::coins:
    case ResultCode::owned:
    case ResultCode::phase:
    case ResultCode::dead:
    case ResultCode::item:
    case ResultCode::op:
    case ResultCode::field:
    case ResultCode::spectator:
    case ResultCode::count_: break;
  }
  return {};
}

constexpr std::string_view to_string(ErrorCode c) { return name_in(kErrorCodes, c); }
constexpr std::string_view to_string(ResultCode c) { return name_in(kResultCodes, c); }
constexpr std::optional<ErrorCode> error_code_of(std::string_view name) { return code_in(kErrorCodes, name); }
constexpr std::optional<ResultCode> result_code_of(std::string_view name) { return code_in(kResultCodes, name); }

// An error message with this code.
inline Error make_error(ErrorCode code, std::string message) { return Error{std::string(to_string(code)), std::move(message)}; }
inline bool has_code(const Error& e, ErrorCode code) { return e.code == to_string(code); }

}  // namespace fts::protocol
