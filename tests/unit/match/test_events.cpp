// Typed ids and events (issue 10, point 4): a BallId is not a PlayerId nor a number; one
// record per event kind, so a reader cannot read a field its kind does not set; the
// variant's order is EventKind's.
#include <catch2/catch.hpp>

#include <type_traits>

#include "fts/sim/match.hpp"

using namespace fts::sim;

// Ids: distinct types, no arithmetic, no silent conversion back to a number.
template <class T> constexpr bool addable = requires(T a) { a + 1; };
static_assert(!std::is_convertible_v<BallId, PlayerId> && !std::is_convertible_v<PlayerId, BallId>);
static_assert(!std::is_convertible_v<BallId, std::uint32_t> && !std::is_convertible_v<PlayerId, std::uint32_t>);
static_assert(!addable<BallId> && !addable<PlayerId>);
static_assert(BallId{3} < BallId{4} && !BallId{} && PlayerId{7}.value == 7);

// A record has only its kind's fields: reading another would not compile.
template <class T> constexpr bool has_player = requires(T e) { e.player; };
template <class T> constexpr bool has_coins = requires(T e) { e.coins; };
template <class T> constexpr bool has_level = requires(T e) { e.level; };
template <class T> constexpr bool has_lives_left = requires(T e) { e.lives_left; };
template <class T> constexpr bool has_ball = requires(T e) { e.ball; };
static_assert(!has_player<LevelComplete> && !has_player<GameOver> && !has_player<LevelStarted>);
static_assert(!has_coins<GameOver> && !has_coins<RocketFired> && !has_coins<PlayerFell>);
static_assert(!has_level<Left> && !has_level<Purchased> && !has_level<InterestPaid>);
static_assert(!has_lives_left<PlayerRespawned> && !has_lives_left<EnemyDefeated>);
static_assert(!has_ball<Purchased> && !has_ball<EnemyDefeated> && !has_ball<RocketFired>);
static_assert(has_player<EnemyDefeated> && has_coins<EnemyDefeated> && has_lives_left<PlayerFell> && has_ball<PlayerFell>);

TEST_CASE("Events: each record's kind and name follow EventKind") {
  const std::vector<std::pair<Event, EventKind>> all = {
      {Joined{}, EventKind::joined},
      {JoinRefused{}, EventKind::join_refused},
      {Left{}, EventKind::left},
      {LevelStarted{}, EventKind::level_started},
      {EnemyDefeated{}, EventKind::enemy_defeated},
      {PlayerFell{}, EventKind::player_fell},
      {PlayerRespawned{}, EventKind::player_respawned},
      {LevelComplete{}, EventKind::level_complete},
      {Purchased{}, EventKind::purchase},
      {RocketFired{}, EventKind::rocket_fired},
      {GameOver{}, EventKind::game_over},
      {InterestPaid{}, EventKind::interest},
  };
  REQUIRE(all.size() == std::variant_size_v<Event>);
  for (const auto& [event, kind] : all) {
    CHECK(kind_of(event) == kind);
    CHECK(to_string(kind_of(event)) != "?");
  }
  CHECK(to_string(kind_of(Event{Purchased{}})) == "purchase");
  CHECK(to_string(kind_of(Event{InterestPaid{}})) == "interest");
}
