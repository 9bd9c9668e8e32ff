// One match of the game as a pure function stepped at fixed ticks:
// events = step(state, inputs). No clock, no I/O; one Rng owned by the state; every
// container is iterated by id. Phases: lobby -> playing -> shop -> playing ... ->
// game_over; "play again" starts a new match at level 1.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "fts/sim/config.hpp"
#include "fts/sim/economy.hpp"
#include "fts/sim/id_map.hpp"
#include "fts/sim/level.hpp"
#include "fts/sim/physics.hpp"
#include "fts/sim/rng.hpp"

namespace fts::sim {


enum class Phase : std::uint8_t { lobby, playing, shop, game_over };
std::string_view to_string(Phase p);

// What a player holds down during one tick.
struct PlayerInput {
  std::int8_t move_x = 0;  // -1, 0, +1
  std::int8_t move_y = 0;  // -1, 0, +1 (y grows up)
  bool fire = false;
};

enum class CommandKind : std::uint8_t { buy, ready, play_again };
struct Command {
  CommandKind kind = CommandKind::ready;
  std::string item;  // buy only: "mass" or "m", ...; anything else is refused as unknown_item
  std::uint32_t tag = 0;  // the caller's, echoed in the command's result (the server's rid);
                          // no part of the match: not recorded, not hashed
};

// The outcome of one command, decided by the code that ran it.
struct CommandResult {
  PlayerId player = 0;
  std::uint32_t tag = 0;  // the command's tag
  CommandKind kind = CommandKind::ready;
  Refusal code = Refusal::none;  // none: done
  Item item = Item::mass;        // buy: the item (mass when the name was unknown)
  Coins price = 0;               // buy: charged, or the price that was refused
  Coins coins_after = 0;         // buy: the buyer's coins after the command
  bool ok() const { return code == Refusal::none; }
};

struct PlayerTick {
  PlayerId player = 0;
  PlayerInput input;
  std::vector<Command> commands;  // applied in order
};
struct JoinRequest {
  PlayerId player = 0;
  std::string name;
};
// Everything that reaches the match for one tick. Applied in player-id order.
struct TickInputs {
  std::vector<JoinRequest> joins;
  std::vector<PlayerId> leaves;
  // Connection presence: an away player keeps its place (for a reconnect) but does not
  // hold up the lobby or the shop ("every connected player ... is ready").
  std::vector<PlayerId> away;
  std::vector<PlayerId> back;
  // Players who quit (bye): away, and their ball leaves the platform at once without
  // costing a life; their progress stays until they leave or come back.
  std::vector<PlayerId> quit;
  std::vector<PlayerTick> players;
};

enum class EventKind : std::uint8_t {
  joined, join_refused, left, level_started, enemy_defeated, player_fell, player_respawned,
  level_complete, purchase, rocket_fired, game_over,
  interest,  // bank interest paid at a level's end (coins)
};
std::string_view to_string(EventKind k);

// One record per event kind, so that a reader sees only the fields its kind sets.
struct Joined {
  PlayerId player = 0;
  std::string name;
};
// Why the match refused a join: one row each, its name (logs, fts-sim's output) and the
// sentence a player reads (the server's error message). The wire's code is the server's
// (ErrorCode::refused); no layer spells these names itself.
enum class JoinRefusal : std::uint8_t { bad_id, id_in_use, match_full, bad_name };
struct JoinRefusalInfo {
  JoinRefusal refusal;
  std::string_view name;
  std::string_view sentence;
};
inline constexpr std::array<JoinRefusalInfo, 4> kJoinRefusals{{
    {JoinRefusal::bad_id, "bad_id", "player id 0 is no player"},
    {JoinRefusal::id_in_use, "id_in_use", "that player id is in the match already"},
    {JoinRefusal::match_full, "match_full", "every seat of the match is taken"},
    {JoinRefusal::bad_name, "bad_name", "the name is empty or longer than 32 bytes"},
}};
static_assert(kJoinRefusals.size() == static_cast<std::size_t>(JoinRefusal::bad_name) + 1);
constexpr const JoinRefusalInfo& join_refusal_info(JoinRefusal r) {
  return kJoinRefusals[static_cast<std::size_t>(r) % kJoinRefusals.size()];
}
constexpr std::string_view to_string(JoinRefusal r) { return join_refusal_info(r).name; }

struct JoinRefused {
  PlayerId player = 0;
  JoinRefusal reason = JoinRefusal::bad_id;
};
struct Left {
  PlayerId player = 0;
};
struct LevelStarted {
  std::int64_t level = 0;
  bool restart = false;  // the same level again after everyone fell
};
struct EnemyDefeated {
  BallId enemy = 0;
  PlayerId player = 0;  // credited; 0: nobody (the enemy fell untouched)
  std::int64_t level = 0;
  Coins coins = 0;      // earned by `player`
};
struct PlayerFell {
  PlayerId player = 0;
  BallId ball = 0;
  std::int64_t level = 0;
  std::int64_t lives_left = 0;
};
struct PlayerRespawned {
  PlayerId player = 0;
  BallId ball = 0;
};
struct LevelComplete {
  std::int64_t level = 0;
};
struct Purchased {  // tried: ok or refused (the buyer's command result says the same)
  PlayerId player = 0;
  std::string asked;  // the item as asked ("m", "mass", or anything)
  Item item = Item::mass;
  bool ok = false;
  Refusal reason = Refusal::none;
  Coins price = 0;
  Coins coins_after = 0;
};
struct RocketFired {
  PlayerId player = 0;
  BallId rocket = 0;
};
struct GameOver {
  std::int64_t level = 0;
};
struct InterestPaid {  // bank interest at a level's end
  PlayerId player = 0;
  Coins coins = 0;
};

// Alternatives in EventKind order.
using Event = std::variant<Joined, JoinRefused, Left, LevelStarted, EnemyDefeated, PlayerFell, PlayerRespawned,
                           LevelComplete, Purchased, RocketFired, GameOver, InterestPaid>;
static_assert(std::variant_size_v<Event> == static_cast<std::size_t>(EventKind::interest) + 1);
inline EventKind kind_of(const Event& e) { return static_cast<EventKind>(e.index()); }

// std::visit with one lambda per record: a kind without a lambda does not compile.
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

enum class BodyKind : std::uint8_t { enemy, player, rocket };
std::string_view to_string(BodyKind k);

// Game data of a ball; its physics lives in World.
struct Body {
  BodyKind kind = BodyKind::enemy;
  PlayerId owner = 0;          // player / rocket
  std::int64_t index = 0;      // enemy index within the level
  EnemySpec spec;              // enemy
  Vec2 goal;                   // enemy
  PlayerId credit = 0;         // enemy: last toucher (directly or through a chain)
  std::int64_t credit_tick = -1;  // tick of that player's originating hit
  std::int64_t expires_tick = 0;  // rocket
};

struct Player {
  PlayerId id = 0;
  std::string name;
  Economy eco;
  bool ready = false;
  BallId ball = 0;                 // 0: not on the platform
  std::int64_t respawn_tick = -1;  // >= 0: put back on the platform at that tick
  // >= 0: the ball is under spawn protection (immovable) while tick < this; -1: not.
  std::int64_t protected_until_tick = -1;
  std::int64_t next_fire_tick = 0;
  Vec2 aim{1.0, 0.0};              // last thrust direction (rockets when standing still)
  bool connected = true;           // false while its client is away (see TickInputs::away)
  bool parked = false;             // quit: no ball, no seat, progress kept (TickInputs::quit)
  bool in_match() const { return eco.lives > 0; }
  bool protected_at(std::int64_t tick) const { return tick < protected_until_tick; }
};

struct MatchState {
  MatchConfig cfg;
  Phase phase = Phase::lobby;
  std::int64_t tick = 0;             // ticks stepped so far
  std::int64_t level = 0;            // current (or just completed, in the shop) level
  std::int64_t levels_cleared = 0;   // in this match
  std::int64_t shop_deadline_tick = 0;
  std::int64_t lobby_deadline_tick = -1;  // -1: nobody ready yet (see lobby_timeout_s)
  std::int64_t matches_started = 0;
  Rng rng;
  World world;
  PhysicsSettings physics;
  StepConstants step_k;
  IdMap<BallId, Body> bodies;    // by ball id, ascending
  std::vector<Player> players;  // sorted by id
  std::uint32_t next_ball_id = 1;  // the next ball's id
};

// A fresh match in the lobby. cfg must be valid (see validate()).
MatchState make_match(const MatchConfig& cfg, std::uint64_t seed);
// What one tick produced: its events, and one result per command it was given, in the
// order the step applied them (player id, then the player's command order).
struct TickOutput {
  std::vector<Event> events;
  std::vector<CommandResult> results;
};
// Advances the match by one tick.
TickOutput step(MatchState& state, const TickInputs& inputs);
// Whether a ready / play-again command from this player takes effect now.
bool accepts_ready(const MatchState& s, const Player& p);
bool accepts_play_again(const MatchState& s);
// FNV-1a over every bit of the state, the Rng included.
std::uint64_t match_hash(const MatchState& state);

// Look-ups (nullptr when absent).
Player* find_player(MatchState& s, PlayerId id);
const Player* find_player(const MatchState& s, PlayerId id);
const Ball* find_ball(const World& w, BallId id);
Ball* find_ball(World& w, BallId id);

}  // namespace fts::sim
