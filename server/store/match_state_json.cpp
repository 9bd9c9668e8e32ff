#include "store/match_state_json.hpp"

#include "store/checkpoint_fields.hpp"

namespace fts::store {
namespace {

using namespace checkpoint;
using sim::BallId;
using sim::Coins;
using I64 = Value<std::int64_t>;

// One table per struct: the one place a checkpoint field is named. Objects have keys;
// the economy, a ball and a body are rows (values by position, in table order), as the
// checkpoints already written have them.
constexpr auto kVec2Fields = std::make_tuple(field("x", &sim::Vec2::x, Value<double>{}),
                                             field("y", &sim::Vec2::y, Value<double>{}));
static_assert(names_every_member<sim::Vec2>(kVec2Fields));

constexpr auto kPricesFields =
    std::make_tuple(field("prices", &sim::Prices::by_item, Array<double, sim::kItemCount>{}));
static_assert(names_every_member<sim::Prices>(kPricesFields));

constexpr auto kEconomyFields = std::make_tuple(
    field("coins", &sim::Economy::coins, Value<Coins>{}), field("lives", &sim::Economy::lives, I64{}),
    field("mass", &sim::Economy::mass, I64{}), field("vmax_u_per_s", &sim::Economy::vmax_u_per_s, Value<double>{}),
    field("accel_u_per_s2", &sim::Economy::accel_u_per_s2, Value<double>{}),
    field("multiplier", &sim::Economy::multiplier, Value<double>{}), field("bank", &sim::Economy::bank, Value<bool>{}),
    field("rockets", &sim::Economy::rockets, Value<bool>{}), field("prices", &sim::Economy::prices, Splice{kPricesFields}),
    field("start_coins", &sim::Economy::start_coins, Value<Coins>{}),
    field("earned_defeats", &sim::Economy::earned_defeats, Value<Coins>{}),
    field("earned_interest", &sim::Economy::earned_interest, Value<Coins>{}),
    field("spent", &sim::Economy::spent, Value<Coins>{}), field("purchases", &sim::Economy::purchases, I64{}),
    field("defeats", &sim::Economy::defeats, I64{}));
static_assert(names_every_member<sim::Economy>(kEconomyFields));
static_assert(row_width(kEconomyFields) == 15);  // checkpoints already written have 15

constexpr auto kPlayerFields = std::make_tuple(
    field("id", &sim::Player::id, IdValue{}), field("name", &sim::Player::name, Value<std::string>{}),
    field("eco", &sim::Player::eco, Row{kEconomyFields}), field("ready", &sim::Player::ready, Value<bool>{}),
    field("ball", &sim::Player::ball, IdValue{}), field("respawn_tick", &sim::Player::respawn_tick, I64{}),
    // Absent in checkpoints written before spawn protection: not protected.
    field("protected_until_tick", &sim::Player::protected_until_tick, I64{}, Presence::defaulted),
    field("next_fire_tick", &sim::Player::next_fire_tick, I64{}), field("aim", &sim::Player::aim, Row{kVec2Fields}),
    field("connected", &sim::Player::connected, Value<bool>{}), field("parked", &sim::Player::parked, Value<bool>{}));
static_assert(names_every_member<sim::Player>(kPlayerFields));

constexpr auto kBallFields = std::make_tuple(
    field("id", &sim::Ball::id, IdValue{}), field("pos", &sim::Ball::pos, Splice{kVec2Fields}),
    field("vel", &sim::Ball::vel, Splice{kVec2Fields}), field("radius", &sim::Ball::radius, Value<double>{}),
    field("mass", &sim::Ball::mass, Value<double>{}),
    field("thrust_axes", &sim::Ball::thrust_axes, Skip{}));  // not state: step() clears it
static_assert(names_every_member<sim::Ball>(kBallFields));
static_assert(row_width(kBallFields) == 7);

constexpr auto kWorldFields = std::make_tuple(field("arena", &sim::World::arena, Skip{}),  // from the config
                                              field("balls", &sim::World::balls, Ascending{Row{kBallFields}}),
                                              field("buffers", &sim::World::buffers, Skip{}));  // the step's memory
static_assert(names_every_member<sim::World>(kWorldFields));

constexpr auto kEnemySpecFields = std::make_tuple(
    field("mass", &sim::EnemySpec::mass, Value<double>{}), field("radius_u", &sim::EnemySpec::radius_u, Value<double>{}),
    field("accel_u_per_s2", &sim::EnemySpec::accel_u_per_s2, Value<double>{}),
    field("vmax_u_per_s", &sim::EnemySpec::vmax_u_per_s, Value<double>{}),
    field("role", &sim::EnemySpec::role, Enum{sim::EnemyRole::chaser}));
static_assert(names_every_member<sim::EnemySpec>(kEnemySpecFields));

constexpr auto kBodyFields = std::make_tuple(
    field("kind", &sim::Body::kind, Enum{sim::BodyKind::rocket}), field("owner", &sim::Body::owner, IdValue{}),
    field("index", &sim::Body::index, I64{}), field("spec", &sim::Body::spec, Splice{kEnemySpecFields}),
    field("goal", &sim::Body::goal, Splice{kVec2Fields}), field("credit", &sim::Body::credit, IdValue{}),
    field("credit_tick", &sim::Body::credit_tick, I64{}), field("expires_tick", &sim::Body::expires_tick, I64{}));
static_assert(names_every_member<sim::Body>(kBodyFields));

// A body as the match holds it: by its ball's id, written first.
struct BodyEntry {
  BallId id;
  sim::Body value;
};
constexpr auto kBodyEntryFields = std::make_tuple(field("id", &BodyEntry::id, IdValue{}),
                                                  field("body", &BodyEntry::value, Splice{kBodyFields}));
static_assert(names_every_member<BodyEntry>(kBodyEntryFields));
static_assert(row_width(kBodyEntryFields) == 14);

using M = sim::MatchState;
constexpr auto kMatchFields = std::make_tuple(
    field("cfg", &M::cfg, Skip{}),  // the journal's header has it; make_match gives what it derives
    field("phase", &M::phase, Enum{sim::Phase::game_over}), field("tick", &M::tick, I64{}),
    field("level", &M::level, I64{}), field("levels_cleared", &M::levels_cleared, I64{}),
    field("shop_deadline_tick", &M::shop_deadline_tick, I64{}),
    field("lobby_deadline_tick", &M::lobby_deadline_tick, I64{}),
    field("matches_started", &M::matches_started, I64{}), field("rng", &M::rng, RngState{}),
    field("world", &M::world, Splice{kWorldFields}), field("physics", &M::physics, Skip{}),
    field("step_k", &M::step_k, Skip{}), field("bodies", &M::bodies, by_id<BodyEntry>(Row{kBodyEntryFields})),
    field("players", &M::players, Ascending{Object{kPlayerFields}}),
    field("next_ball_id", &M::next_ball_id, Value<std::uint32_t>{}));
static_assert(names_every_member<M>(kMatchFields));

}  // namespace

nlohmann::json match_state_to_json(const sim::MatchState& s) {
  nlohmann::json j = nlohmann::json::object();
  write_object(j, s, kMatchFields);
  return j;
}

std::variant<sim::MatchState, std::string> match_state_from_json(const nlohmann::json& j, sim::MatchState s) {
  if (!j.is_object()) return std::string("checkpoint: not an object");
  try {
    read_object(j, s, kMatchFields);
  } catch (const std::exception& e) {
    return std::string("checkpoint: ") + e.what();
  }
  return s;
}

}  // namespace fts::store
