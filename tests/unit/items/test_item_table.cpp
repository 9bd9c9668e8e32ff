// Issue 10, point 2: an item's rules live in one row of common's item table, its numbers
// in MatchConfig. A changed price rule and changed shop terms reach the match, the wire,
// the HUD's shop screen, the match's shop text and the bots together.
#include <catch2/catch.hpp>

#include <algorithm>

#include "../match/match_test_util.hpp"
#include "app/game_host.hpp"
#include "fts/room/snapshot_build.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/snapshot_delta.hpp"
#include "fts/sim/bot_player.hpp"
#include "fts/sim/match_view.hpp"
#include "fts/sim/shop_text.hpp"
#include "ui/hud.hpp"

using namespace fts;
using namespace fts::sim;

namespace {

// A message through the wire (MessagePack datagram) and back.
protocol::Message through_wire(const protocol::Message& m) {
  const auto bytes = protocol::encode_datagram(protocol::Header{}, {m});
  auto d = protocol::decode_datagram(bytes);
  REQUIRE(d.ok());
  REQUIRE(d->messages.size() == 1);
  return d->messages[0];
}

// The match's public state as a client reconstructs it from a full snapshot.
protocol::Snapshot client_snapshot(const MatchState& s) {
  const protocol::Snapshot sent = room::build_snapshot(make_view(s), {});
  const auto msg = std::get<protocol::SnapshotMsg>(through_wire(protocol::make_snapshot_msg(sent, nullptr)));
  auto snap = protocol::apply_snapshot({msg}, nullptr);
  REQUIRE(snap.ok());
  return *snap;
}

bool has_line(const std::vector<std::string>& lines, const std::string& line) {
  return std::find(lines.begin(), lines.end(), line) != lines.end();
}

bool buys(const PlayerTick& t, Item item) {
  return t.commands.size() == 1 && t.commands[0].kind == CommandKind::buy && parse_item(t.commands[0].item) == item;
}

}  // namespace

TEST_CASE("Item table: one row per item, keys and names unique, in the wire's order") {
  REQUIRE(item_table().size() == kItemCount);
  for (std::size_t i = 0; i < kItemCount; ++i) {
    const ItemDef& d = item_table()[i];
    CHECK(index_of(d.item) == i);
    CHECK(item_by_key(d.key) == d.item);
    CHECK(parse_item(d.id) == d.item);
    CHECK(protocol::shop_index(d.key) == static_cast<int>(i));
    for (std::size_t j = i + 1; j < kItemCount; ++j) {
      CHECK(item_table()[j].key != d.key);
      CHECK(item_table()[j].id != d.id);
    }
  }
  CHECK(protocol::shop_index('q') == -1);
  CHECK(percent_text(1.1) == "10");
  CHECK(percent_text(1.2) == "20");
  CHECK(percent_text(1.025) == "2.5");
}

TEST_CASE("Item table: a changed price rule and shop terms reach match, wire, HUD, shop text and bots") {
  MatchConfig cfg;
  cfg.price_speed = 80;            // start price
  cfg.price_speed_growth = 1.5;    // price rule: floor(price x 1.5)
  cfg.price_mass = 1'000'000;      // out of reach: the bots can only want speed
  cfg.price_accel = 1'000'000;
  cfg.price_bank = 1'000'000;
  cfg.bank_interest_factor = 1.2;  // "Earns 20% interest per round"
  cfg.multiplier_upgrade_factor = 1.25;
  cfg.player_coins = 1000;
  REQUIRE(validate(cfg).empty());

  MatchState s = test::started(1, 1, cfg);
  test::remove_enemies(s);
  const BallId e = test::add_enemy(s, {499, 150}, {200, 0});
  s.bodies[e].credit = 1;
  step(s, {});
  REQUIRE(s.phase == Phase::shop);
  TickInputs in;
  in.players.push_back({1, {}, {{CommandKind::buy, "s", 1}}});
  const TickOutput out = step(s, in);
  REQUIRE(out.results.size() == 1);
  CHECK(out.results[0].ok());
  CHECK(out.results[0].price == 80);

  // Match: the next price follows the configured rule.
  Player& me = *find_player(s, 1);
  CHECK(price_of(me.eco, Item::speed) == 120);

  // Wire: the snapshot carries it at the item's place.
  const protocol::Snapshot snap = client_snapshot(s);
  REQUIRE(snap.players.size() == 1);
  const protocol::PlayerState& wire = snap.players[0];
  CHECK(wire.prices[index_of(Item::speed)] == 120);
  CHECK(wire.prices[index_of(Item::bank)] == 1'000'000);

  // The welcome carries the terms the shop states.
  const server::Options options;
  protocol::Welcome sent = server::make_endpoint_config(options, cfg, protocol::ServerKey{}).settings;
  sent.player_id = 1;  // the endpoint fills these in per session
  sent.token = std::string(32, 'a');
  const auto welcome = std::get<protocol::Welcome>(through_wire(sent));
  CHECK(welcome.shop() == shop_terms(cfg));

  // HUD's shop screen (from the wire) == the match's shop text (from the state).
  const auto screen = client::shop_screen_lines(wire, snap.level, welcome.shop());
  const auto text = shop_lines(me.eco, s.level, shop_terms(cfg));
  CHECK(screen == text);
  CHECK(has_line(screen, "To increase Max Speed, press 's' (120 coins)"));
  CHECK(has_line(screen, "Increases coins from enemies by 25%"));
  CHECK(has_line(screen, "Earns 20% interest per round"));
  CHECK_FALSE(has_line(screen, "Earns 10% interest per round"));

  // Bots: the built-in bot and fts-bot's shop choice (prices from the wire) both follow.
  ShopSight sight;
  sight.lives = wire.lives;
  sight.accel_u_per_s2 = wire.accel_u_per_s2;
  sight.vmax_u_per_s = wire.vmax_u_per_s;
  sight.mass = static_cast<std::int64_t>(wire.mass);
  sight.prices = wire.prices;
  for (const Coins coins : {Coins{119}, Coins{120}}) {
    INFO("coins " << coins);
    me.eco.coins = coins;
    sight.coins = coins;
    const bool afford = coins >= 120;
    CHECK(buys(bot_tick(s, 1), Item::speed) == afford);
    CHECK((bot_shop_choice(sight) == Item::speed) == afford);
  }
}
