// The field tables of the handshake and control messages (internal); the snapshot's and
// the input's are in tables.hpp. One row per wire key, documented in PROTOCOL.md 4.
#pragma once

#include <cmath>
#include <tuple>
#include <type_traits>

#include "fields.hpp"
#include "fts/protocol/messages.hpp"
#include "fts/sim/config_fields.hpp"

namespace fts::protocol::wire {

inline constexpr std::size_t kTokenHex = 32;
inline constexpr std::size_t kSealedTokenHex = 96;  // a token sealed in a hello (PROTOCOL.md 5.7.3)
inline constexpr std::size_t kKeyHex = 64;          // a crypto_kx public key (5.7.1)
inline constexpr std::size_t kCookieHex = 48;
inline constexpr std::size_t kNonceHex = 16;
inline constexpr std::size_t kSealedIdentityHex = 224;  // the hello's identity box (PROTOCOL.md 5.8)
inline constexpr std::size_t kRoomBytes = 16;
inline constexpr std::size_t kCodeBytes = 32;
inline constexpr std::int64_t kAnyU32 = 0xFFFFFFFF;

template <class M, class T, class K>
using F = Field<M, T, K>;
using U32 = Int<std::uint32_t>;

// ---- hello (PROTOCOL.md 4.1)
inline constexpr auto kHelloFields = std::make_tuple(
    F<Hello, std::string, AnyText>{"name", &Hello::name, {kMaxTextBytes}},
    F<Hello, std::string, Hex>{"token", &Hello::token, {kSealedTokenHex}},
    F<Hello, std::string, Hex>{"cookie", &Hello::cookie, {kCookieHex}},
    F<Hello, std::string, Text>{"pad", &Hello::pad, {0, kMaxDatagramBytes}},
    F<Hello, std::string, Hex>{"nonce", &Hello::nonce, {kNonceHex, true}},
    F<Hello, std::string, Text>{"join", &Hello::join, {0, kRoomBytes}, Presence::nonzero},
    F<Hello, std::string, Text>{"room", &Hello::room, {0, kRoomBytes}, Presence::nonzero},
    F<Hello, std::string, Hex>{"key", &Hello::key, {kKeyHex}, Presence::nonzero},
    F<Hello, std::string, Hex>{"id", &Hello::id, {kSealedIdentityHex}, Presence::nonzero});

// ---- challenge (4.2)
inline constexpr auto kChallengeFields =
    std::make_tuple(F<Challenge, std::string, Hex>{"cookie", &Challenge::cookie, {kCookieHex, true}},
                    F<Challenge, std::string, Hex>{"key", &Challenge::key, {kKeyHex, true}});

// ---- welcome (4.3)
// A number of the match's configuration, written as an integer when it is a whole one:
// tick_rate_hz was an integer key before it came from the configuration, and readers of
// that time still read it as one (any reader takes an integer for a number).
struct ConfigNum : Num {
  template <class W>
  void put(W& w, double v) const {
    if (std::isfinite(v) && std::fabs(v) < 9e15 && static_cast<double>(static_cast<std::int64_t>(v)) == v)
      w.integer(static_cast<std::int64_t>(v));
    else Num::put(w, v);
  }
};

// A key of the configuration as the welcome writes it: always (`always`), or only when it
// is not the default (what an older server's welcome lacks reads as that default).
template <class K, class T>
struct UnlessDefault : K {
  T fallback;
  bool always;
  constexpr bool present(const T& v) const { return always || !(v == fallback); }
};

// The welcome's row of a field of the match configuration (a client_row of
// config_fields.hpp): its own key, its kind from its type, lo..hi its range.
template <class T>
constexpr auto config_row(const fields::Field<sim::MatchConfig, T, sim::ClientKey>& row) {
  const double lo = row.kind.lo, hi = row.kind.hi;
  auto kind = [&] {
    if constexpr (std::is_same_v<T, double>) {
      return ConfigNum{{lo, hi}};
    } else if constexpr (std::is_same_v<T, sim::Model>) {
      static_assert(static_cast<int>(sim::Model::continuous) == 2);
      return Named<sim::Model, 3>{{"seed", "discrete", "continuous"}};
    } else {
      static_assert(std::is_integral_v<T>, "a kind for this type of config field");
      return Int<T>{static_cast<std::int64_t>(lo), static_cast<std::int64_t>(hi)};
    }
  }();
  using O = UnlessDefault<decltype(kind), T>;
  const bool always = row.presence == Presence::required;
  return SubField<Welcome, sim::MatchConfig, T, O>{row.key, &Welcome::match, row.member,
                                                   O{kind, sim::MatchConfig{}.*row.member, always}, row.presence};
}

// The welcome's rows of the configuration: one per client_row of kMatchConfigFields.
template <class Row>
constexpr auto welcome_config_rows(const Row& row) {
  if constexpr (sim::is_client_key<decltype(row.kind)>) return std::make_tuple(config_row(row));
  else return std::tuple<>{};
}
inline constexpr auto kWelcomeConfigFields =
    std::apply([](const auto&... row) { return std::tuple_cat(welcome_config_rows(row)...); }, sim::kMatchConfigFields);

inline constexpr auto kWelcomeFields = std::tuple_cat(
    std::make_tuple(
        F<Welcome, std::uint32_t, U32>{"player_id", &Welcome::player_id, {1, kAnyU32}},
        F<Welcome, std::string, Hex>{"token", &Welcome::token, {kTokenHex}},
        F<Welcome, std::uint32_t, U32>{"snapshot_rate_hz", &Welcome::snapshot_rate_hz, {0, 10000}},
        F<Welcome, std::uint32_t, U32>{"max_players", &Welcome::max_players, {0, 64}},
        F<Welcome, std::uint32_t, U32>{"timeout_ms", &Welcome::timeout_ms, {0, kAnyU32}},
        F<Welcome, std::uint32_t, U32>{"reconnect_window_ms", &Welcome::reconnect_window_ms, {0, kAnyU32}},
        F<Welcome, std::uint32_t, U32>{"input_redundancy", &Welcome::input_redundancy, {0, kMaxInputFrames}},
        F<Welcome, std::uint32_t, U32>{"server_tick", &Welcome::server_tick, {0, kAnyU32}},
        F<Welcome, bool, Bool>{"reconnected", &Welcome::reconnected, {}}),
    kWelcomeConfigFields,
    std::make_tuple(F<Welcome, std::string, Text>{"room", &Welcome::room, {0, kRoomBytes}, Presence::nonzero},
                    F<Welcome, bool, Bool>{"spectator", &Welcome::spectator, {}, Presence::nonzero}));

// ---- error (4.4)
inline constexpr auto kErrorFields =
    std::make_tuple(F<Error, std::string, Text>{"code", &Error::code, {0, kCodeBytes}},
                    F<Error, std::string, Text>{"msg", &Error::message, {0, kMaxTextBytes}});

// ---- cmd (4.6): lenient on purpose: an op or item the server cannot apply still reads,
// and a field of the wrong type, range or length reads as its default with its key in
// Command::fault, so that the command is consumed and answered instead of blocking the
// reliable channel. Only the rid must read: without it there is nothing to answer. The
// chat text takes any bytes (the server cleans it).
// The ops by their names on the wire, in CommandOp's order; any other name reads as unknown.
inline constexpr std::array<const char*, 8> kCommandOpNames{"buy",   "ready", "again", "unknown",
                                                            "chat", "rooms", "top",   "forget"};
inline constexpr auto kCommandFields = std::make_tuple(
    F<Command, std::uint32_t, U32>{"rid", &Command::rid, {0, kAnyU32}},
    F<Command, CommandOp, Tolerant<OpenNamed<CommandOp, 8>>>{"op", &Command::op, {{kCommandOpNames, CommandOp::unknown}}},
    F<Command, char, Tolerant<Key>>{"item", &Command::item, {}, Presence::nonzero},
    F<Command, std::string, Tolerant<AnyText>>{"text", &Command::text, {{kMaxTextBytes}}, Presence::nonzero});

// ---- result (4.7)
inline constexpr auto kResultFields = std::make_tuple(
    F<Result, std::uint32_t, U32>{"rid", &Result::rid, {1, kAnyU32}},
    F<Result, std::uint32_t, U32>{"cmd", &Result::command_rid, {0, kAnyU32}},
    F<Result, bool, Bool>{"ok", &Result::ok, {}},
    F<Result, std::string, Text>{"code", &Result::code, {0, kCodeBytes}},
    F<Result, std::string, Text>{"msg", &Result::message, {0, kMaxTextBytes}});

// ---- chat (4.7b)
inline constexpr auto kChatFields = std::make_tuple(
    F<Chat, std::uint32_t, U32>{"rid", &Chat::rid, {1, kAnyU32}},
    F<Chat, std::uint32_t, U32>{"from", &Chat::from, {0, kAnyU32}},
    F<Chat, std::string, Text>{"name", &Chat::name, {0, kMaxNameBytes}},
    F<Chat, std::string, Text>{"text", &Chat::text, {0, kMaxTextBytes}});

// ---- ping (4.8): no fields
inline constexpr std::tuple<> kPingFields{};

// ---- bye (4.9)
// A reason that does not read (not text, longer than 200 bytes, not printable) is refused
// like any other bad field: the datagram is dropped and the session goes on (3, 4.9).
inline constexpr auto kByeFields =
    std::make_tuple(F<Bye, std::string, Text>{"reason", &Bye::reason, {0, kMaxTextBytes}});

// ---- moved (4.9b): an address is a host name or address and a port ("[::1]:7777" for
// IPv6); 2..255 bytes, printable.
inline constexpr std::size_t kAddressBytes = 255;
inline constexpr auto kMovedFields =
    std::make_tuple(F<Moved, std::string, Text>{"addr", &Moved::address, {2, kAddressBytes}},
                    F<Moved, std::string, Text>{"room", &Moved::room, {0, kRoomBytes}});

}  // namespace fts::protocol::wire
