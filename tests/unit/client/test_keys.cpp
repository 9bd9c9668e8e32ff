#include <catch2/catch.hpp>

#include "term/keys.hpp"

using namespace fts::client;
using fts::protocol::Phase;

TEST_CASE("legacy key bytes decode", "[client][keys]") {
  KeyDecoder d;
  auto ev = d.feed("w\x1b[A\x1bOD \r\x03q");
  REQUIRE(ev.size() == 7);
  CHECK(ev[0] == KeyEvent{Key::character, 'w'});
  CHECK(ev[1].key == Key::up);
  CHECK(ev[2].key == Key::left);
  CHECK(ev[3].key == Key::space);
  CHECK(ev[4].key == Key::enter);
  CHECK(ev[5].key == Key::ctrl_c);
  CHECK(ev[6] == KeyEvent{Key::character, 'q'});
  SECTION("a sequence split across reads waits for the rest") {
    CHECK(d.feed("\x1b[").empty());
    CHECK(d.pending());
    auto rest = d.feed("C");
    REQUIRE(rest.size() == 1);
    CHECK(rest[0].key == Key::right);
  }
  SECTION("a lone escape is the Escape key once flushed") {
    CHECK(d.feed("\x1b").empty());
    auto f = d.flush();
    REQUIRE(f.size() == 1);
    CHECK(f[0].key == Key::escape);
  }
  SECTION("modified arrows still move") {
    auto m = d.feed("\x1b[1;5B");
    REQUIRE(m.size() == 1);
    CHECK(m[0].key == Key::down);
    CHECK_FALSE(m[0].kitty);
  }
}

TEST_CASE("kitty keyboard protocol events decode with their type", "[client][keys]") {
  KeyDecoder d;
  CHECK(kitty_push() == "\x1b[>11u");
  KeyDecoder no_events;
  CHECK(no_events.feed("\x1b[?1u").empty());
  CHECK_FALSE(no_events.kitty_supported());  // flags without "report event types"
  CHECK(d.feed("\x1b[?11u").empty());
  CHECK(d.kitty_supported());
  auto ev = d.feed("\x1b[119u\x1b[119;1:2u\x1b[119;1:3u\x1b[1;1:3C\x1b[13u\x1b[99;5u\x1b[32;1:1u\x1b[87;2u");
  REQUIRE(ev.size() == 8);
  CHECK(ev[0] == KeyEvent{Key::character, 'w', KeyAction::press, true});
  CHECK(ev[1].action == KeyAction::repeat);
  CHECK(ev[2].action == KeyAction::release);
  CHECK(ev[3] == KeyEvent{Key::right, 0, KeyAction::release, true});
  CHECK(ev[4].key == Key::enter);
  CHECK(ev[5].key == Key::ctrl_c);
  CHECK(ev[6].key == Key::space);
  CHECK(ev[7] == KeyEvent{Key::character, 'w', KeyAction::press, true});  // shift+w
  // After the query's answer, even a plain arrow press promises a release.
  auto plain = d.feed("\x1b[A");
  REQUIRE(plain.size() == 1);
  CHECK(plain[0] == KeyEvent{Key::up, 0, KeyAction::press, true});
  // Unknown functional keys and modifiers alone are ignored.
  CHECK(d.feed("\x1b[57441u\x1b[15~").empty());
}

TEST_CASE("holding a key without release events uses the repeat time-out", "[client][keys]") {
  HoldTracker h({500, 100});
  const KeyEvent right{Key::right};
  h.on_key(Direction::right, right, 1000);
  CHECK(h.move_x(1000) == 1);
  CHECK(h.move_x(1499) == 1);  // waiting for the terminal's auto-repeat to start
  h.on_key(Direction::right, right, 1450);  // first repeat
  CHECK(h.move_x(1549) == 1);
  CHECK(h.move_x(1551) == 0);  // no more repeats: let go
  SECTION("the opposite key takes over at once") {
    h.on_key(Direction::right, right, 2000);
    h.on_key(Direction::left, KeyEvent{Key::left}, 2010);
    CHECK(h.move_x(2020) == -1);
  }
  SECTION("both axes at once") {
    h.on_key(Direction::up, KeyEvent{Key::character, 'w'}, 3000);
    h.on_key(Direction::right, right, 3000);
    CHECK(h.move_y(3001) == 1);
    CHECK(h.move_x(3001) == 1);
  }
}

TEST_CASE("kitty key releases end the hold without a time-out", "[client][keys]") {
  HoldTracker h;
  h.on_key(Direction::up, KeyEvent{Key::up, 0, KeyAction::press, true}, 1000);
  CHECK(h.move_y(60'000) == 1);
  h.on_key(Direction::up, KeyEvent{Key::up, 0, KeyAction::release, true}, 60'001);
  CHECK(h.move_y(60'002) == 0);
}

TEST_CASE("keys mean different things in play and in the shop", "[client][keys]") {
  const KeyEvent s{Key::character, 's'};
  CHECK(action_of(s, Phase::play).kind == ActionKind::move);
  CHECK(action_of(s, Phase::shop).kind == ActionKind::buy);
  CHECK(action_of(s, Phase::shop).item == 's');
  CHECK(action_of(KeyEvent{Key::character, 'l'}, Phase::shop).item == 'l');
  CHECK(action_of(KeyEvent{Key::character, 'l', KeyAction::release, true}, Phase::shop).kind == ActionKind::none);
  CHECK(action_of(KeyEvent{Key::enter}, Phase::shop).kind == ActionKind::ready);
  CHECK(action_of(KeyEvent{Key::enter}, Phase::over).kind == ActionKind::ready);
  CHECK(action_of(KeyEvent{Key::space}, Phase::play).kind == ActionKind::fire);
  CHECK(action_of(KeyEvent{Key::character, 'q'}, Phase::shop).kind == ActionKind::quit);
  CHECK(action_of(KeyEvent{Key::ctrl_c}, Phase::play).kind == ActionKind::quit);
}
