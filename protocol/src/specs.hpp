// Every message type's wire name and field table (internal), in Message's variant order:
// what the codec's writers and readers dispatch on. Each table names every member of its
// message (fts/sim/field_table.hpp), or the member is listed after it, left off the wire.
#pragma once

#include <string_view>

#include "control_tables.hpp"
#include "tables.hpp"

namespace fts::protocol::wire {

template <class M>
struct Spec;

#define FTS_WIRE_SPEC(M, NAME, TABLE, ...)                                                   \
  static_assert(::fts::fields::names_every_member<M>(TABLE __VA_OPT__(, ) __VA_ARGS__),      \
                #M ": a member without a row in " #TABLE);                                  \
  template <>                                                                                \
  struct Spec<M> {                                                                           \
    static constexpr std::string_view type = NAME;                                           \
    static const auto& fields() { return TABLE; }                                            \
  }

FTS_WIRE_SPEC(Hello, "hello", kHelloFields);
FTS_WIRE_SPEC(Challenge, "challenge", kChallengeFields);
FTS_WIRE_SPEC(Welcome, "welcome", kWelcomeFields);
FTS_WIRE_SPEC(Error, "error", kErrorFields);
FTS_WIRE_SPEC(Input, "input", kInputFields);
FTS_WIRE_SPEC(Command, "cmd", kCommandFields, &Command::fault);  // a read's outcome
FTS_WIRE_SPEC(Result, "result", kResultFields);
FTS_WIRE_SPEC(Ping, "ping", kPingFields);
FTS_WIRE_SPEC(Bye, "bye", kByeFields);
FTS_WIRE_SPEC(SnapshotMsg, "snap", kSnapFields);
FTS_WIRE_SPEC(Chat, "chat", kChatFields);
FTS_WIRE_SPEC(Leaderboard, "board", kLeaderboardFields);
FTS_WIRE_SPEC(Moved, "moved", kMovedFields);

#undef FTS_WIRE_SPEC

// Checks across fields, after a table read (the snapshot's are in tables.hpp).
template <class M>
void check(MsgpackReader&, const M&) {}

}  // namespace fts::protocol::wire
