// Every message of the protocol, declared once. Each has one field table
// (src/control_tables.hpp, src/tables.hpp) from which both encodings, JSON text and
// MessagePack, are written and read (codec.hpp). Field units are in the names or comments.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "fts/protocol/constants.hpp"
#include "fts/protocol/snapshot.hpp"

namespace fts::protocol {

// client -> server, before and during the handshake. Padded to kMinHelloBytes.
struct Hello {
  std::string name;    // 1..16 printable ASCII characters (checked by the server, which
                       // answers a bad one with error{code:"bad_name"})
  std::string token;   // "" or the session token of a previous welcome, sealed (96 hex
                       // digits, PROTOCOL.md 5.7.3): it never travels in clear
  std::string cookie;  // "" or the 48-hex-digit cookie of a challenge
  std::string pad;     // ignored filler, any printable ASCII
  std::string nonce;   // 16 hex digits, new for every connection attempt: a repeated
                       // hello with the same nonce is the same attempt (same welcome)
  // Which room to join (PROTOCOL.md 4.6): "" or "quick", "create", "join", "spectate";
  // absent on the wire when empty (quick play).
  // (Default member initializers: brace-initialised hellos need not name them.)
  std::string join = "";
  std::string room = "";  // the room's code for join and spectate (5 letters), else ""
  // The client's crypto_kx public key for this attempt (64 hex digits; required with a
  // cookie, PROTOCOL.md 5.7).
  std::string key = "";
  // The player's identity proven (PROTOCOL.md 5.8, identity.hpp): "" (a guest, and in a
  // hello without a cookie) or 224 hex digits, a sealed box.
  std::string id = "";

  bool operator==(const Hello&) const = default;
};

// server -> client: prove you receive at your address by sending this cookie back.
struct Challenge {
  std::string cookie;  // 48 hex digits
  std::string key;     // the server's crypto_kx public key (64 hex digits, PROTOCOL.md 5.7)
  bool operator==(const Challenge&) const = default;
};

// server -> client: the handshake is complete. The first sealed datagram (PROTOCOL.md 5.7).
struct Welcome {
  std::uint32_t player_id = 0;
  std::string token;  // 32 hex digits; keep it to reconnect (only ever sent sealed)
  std::uint32_t snapshot_rate_hz = 20;
  std::uint32_t max_players = 8;
  std::uint32_t timeout_ms = 10000;
  std::uint32_t reconnect_window_ms = 60000;
  std::uint32_t input_redundancy = 3;  // send at least this many recent input frames
  std::uint32_t server_tick = 0;
  bool reconnected = false;
  std::string room = "";   // the code of the room joined ("" from a server without rooms)
  bool spectator = false;  // joined to watch: no ball, no seat, inputs ignored
  // The match's configuration as far as a client needs it: every field config_fields.hpp
  // marks CLIENT (tick rate, arena, physics model, sub-steps, friction, frame, the shop's
  // factors), each under its own key; every other field at its default. The client
  // predicts its ball with exactly this (sim::client_part() on the server's config).
  sim::MatchConfig match = {};

  // Whole ticks per second (fts-server runs whole rates; 100 when the number is not one).
  std::uint32_t tick_rate_hz() const;
  // What the shop screen states: the server's frame and factors.
  sim::ShopTerms shop() const { return sim::shop_terms(match); }

  bool operator==(const Welcome&) const = default;
};

// server -> client: a refusal or a fatal error; the connection is over.
struct Error {
  std::string code;     // one of kErrorCodes (codes.hpp), or a code this version does not know
  std::string message;  // a sentence a person can act on
  bool operator==(const Error&) const = default;
};

// One tick of a player's controls.
struct InputFrame {
  std::uint32_t seq = 0;  // client input sequence, 1, 2, 3, ... per session
  std::int8_t move_x = 0;  // -1 left, 0, +1 right
  std::int8_t move_y = 0;  // -1 down, 0, +1 up
  bool fire = false;
  // The server tick this frame is meant for (PROTOCOL.md 4.5): a predicting client says
  // at which tick its ball started doing what it shows; 0: at once, when it arrives.
  std::uint32_t tick = 0;
  bool operator==(const InputFrame&) const = default;
};

// client -> server, unreliable: the latest few input frames (redundant) and the tick of
// the latest complete snapshot received (0: none). Also the client's heartbeat.
struct Input {
  std::uint32_t snapshot_ack = 0;
  std::vector<InputFrame> frames;  // any order, at most kMaxInputFrames
  bool operator==(const Input&) const = default;
};

// unknown: an op this server does not know (answered with code "op", never applied).
// chat: a chat line (text); rooms: asks for the room list, answered in the result's
// message; top: asks for the leaderboard, answered by a result and a Leaderboard;
// forget: erases the profile of the session's identity (PROTOCOL.md 4.6, 4.7c).
enum class CommandOp : std::uint8_t {
  buy = 0, ready = 1, play_again = 2, unknown = 3, chat = 4, rooms = 5, top = 6, forget = 7
};

// client -> server, reliable: applied exactly once, in rid order, answered by a Result.
struct Command {
  std::uint32_t rid = 0;  // reliable id, 1, 2, 3, ... per session
  CommandOp op = CommandOp::ready;
  char item = 0;  // buy only: an item's shop key (m s a r l x b); 0 when missing or not one character
  std::string text;  // chat only: the line said (<= kMaxTextBytes; the server cuts and cleans it)
  // Not on the wire: the key of the first field a receiver could not read ("" when all
  // read). The server answers such a command without applying it (PROTOCOL.md 4.6).
  std::string fault;
  bool operator==(const Command&) const = default;
};

// server -> client, reliable (its own rid sequence): a chat line, or an announcement of
// the host (from == 0, name "host"). The text is sanitised by the server and again by
// the client.
struct Chat {
  std::uint32_t rid = 0;   // 1, 2, 3, ... per session
  std::uint32_t from = 0;  // the sender's player id; 0: the host
  std::string name;        // the sender's name ("host" for an announcement)
  std::string text;
  bool operator==(const Chat&) const = default;
};

// server -> client, reliable: the outcome of one Command.
struct Result {
  std::uint32_t rid = 0;  // server's reliable id, 1, 2, 3, ... per session
  std::uint32_t command_rid = 0;  // the Command this answers
  bool ok = false;
  std::string code;     // one of kResultCodes (codes.hpp), or a code this version does not know
  std::string message;  // human readable
  bool operator==(const Result&) const = default;
};

// One row of the leaderboard (PROTOCOL.md 4.7c): best level, ties by that match's coins.
struct BoardRow {
  std::uint32_t rank = 0;  // 1-based
  std::string name;        // the name last played under (1..16 printable ASCII; the
                           // server cleans what its database holds, the client again)
  std::int64_t level = 0;  // the best level reached
  std::int64_t coins = 0;  // the coins of the match that reached it
  bool operator==(const BoardRow&) const = default;
};

// server -> client, unreliable: the leaderboard of the server's profiles, answering a
// `cmd top` (a result answers the command too; a lost board is asked for again).
struct Leaderboard {
  std::uint32_t cmd = 0;       // the rid of the `cmd top` this answers
  std::vector<BoardRow> top;   // the first rows, at most kBoardRows
  std::uint32_t of = 0;        // players on the board (a match recorded)
  std::uint32_t rank = 0;      // yours; 0: a guest, or no match of yours recorded yet
  std::int64_t best = 0;       // your best level (0: none)
  std::int64_t best_coins = 0; // the coins of that match
  bool operator==(const Leaderboard&) const = default;
};

// Either way: keeps the connection alive and carries the header's acks.
struct Ping {
  bool operator==(const Ping&) const = default;
};

// Either way: a clean disconnect.
struct Bye {
  std::string reason;
  bool operator==(const Bye&) const = default;
};

// server -> client: the player's room now runs on another server (PROTOCOL.md 4.9b, issue
// 42). The client connects there with the token it holds; this session is over.
struct Moved {
  std::string address;  // "host:port" of the room's new server
  std::string room;     // the room's code (the same there)
  bool operator==(const Moved&) const = default;
};

// A ball in a snapshot message, in quantized units (1/16 u, 1/16 u/s). A full entry has
// every field; a motion entry (full == false) holds only the differences of vx, vy from
// the same ball in the base snapshot, and of x, y from where the base's velocity takes
// it (PROTOCOL.md 8.2: with the snap's tick_rate_hz; plain differences when that is 0).
struct BallEntry {
  std::uint32_t id = 0;
  bool full = true;
  std::int64_t x = 0, y = 0, vx = 0, vy = 0;
  std::int64_t radius = 0, mass = 0;
  BallKind kind = BallKind::enemy;
  std::uint32_t owner = 0;
  bool operator==(const BallEntry&) const = default;
};

// A player in a snapshot message: in a full snapshot every field is set; in a delta only
// the fields that changed since the base.
struct PlayerEntry {
  std::uint32_t id = 0;
  std::optional<std::string> name;
  std::optional<std::int64_t> coins;
  std::optional<std::int32_t> lives;
  std::optional<double> mass, vmax_u_per_s, accel_u_per_s2, multiplier;
  std::optional<bool> bank;
  std::optional<Weapon> weapon;
  std::optional<std::array<std::int64_t, sim::kItemCount>> prices;
  std::optional<bool> ready, alive;
  std::optional<std::uint32_t> protected_until_tick;
  std::optional<bool> away;
  bool operator==(const PlayerEntry&) const = default;
};

// server -> client, unreliable: one part of a snapshot (full, or a delta against `base`).
struct SnapshotMsg {
  std::uint32_t tick = 0;
  std::optional<std::uint32_t> base;  // absent: full snapshot
  std::uint32_t part = 0;             // 0 .. parts-1
  std::uint32_t parts = 1;
  Phase phase = Phase::lobby;
  std::uint32_t level = 0;
  std::uint32_t deadline_tick = 0;   // 0: no countdown (absent on the wire)
  std::uint32_t tick_rate_hz = 0;    // delta: ticks per second, for the motion prediction (0: none)
  std::vector<BallEntry> balls;      // new or changed balls of this part (full entries first)
  std::vector<std::uint32_t> gone;   // balls of the base that no longer exist
  std::vector<PlayerEntry> players;  // new or changed players of this part
  std::vector<std::uint32_t> left;   // players of the base that no longer exist
  std::vector<Event> events;         // recent events (delta: newer than the base tick)
  bool operator==(const SnapshotMsg&) const = default;
};

using Message = std::variant<Hello, Challenge, Welcome, Error, Input, Command, Result, Ping,
                             Bye, SnapshotMsg, Chat, Leaderboard, Moved>;

// Why a player name is refused ("" if it is fine): 1..16 printable ASCII characters.
std::string name_problem(const std::string& name);

// The wire name of a message type ("hello", "challenge", ... "snap").
const char* message_type(const Message& message);

}  // namespace fts::protocol
