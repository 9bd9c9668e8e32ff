#include <catch2/catch.hpp>
#include <cmath>

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

TEST_CASE("a tap is a short impulse, a repeating key a hold", "[client][keys]") {
  HoldTracker h({130, 100, 650});
  const KeyEvent right{Key::right};
  h.on_key(Direction::right, right, 1000);
  CHECK(h.move_x(1000) == 1);
  CHECK(h.move_x(1129) == 1);
  CHECK(h.move_x(1130) == 0);  // a tap: 130 ms of thrust, not the terminal's repeat delay
  h.on_key(Direction::right, right, 1500);  // the terminal's first auto-repeat
  CHECK(h.move_x(1599) == 1);
  h.on_key(Direction::right, right, 1530);  // repeats every ~30 ms: held
  CHECK(h.move_x(1629) == 1);
  CHECK(h.move_x(1631) == 0);  // no more repeats: let go
  SECTION("a new tap long after is a tap again") {
    h.on_key(Direction::right, right, 5000);
    CHECK(h.move_x(5129) == 1);
    CHECK(h.move_x(5131) == 0);
  }
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

TEST_CASE("vi keys steer like the arrows", "[client][keys]") {
  CHECK(direction_of(KeyEvent{Key::character, 'h'}) == Direction::left);
  CHECK(direction_of(KeyEvent{Key::character, 'j'}) == Direction::down);
  CHECK(direction_of(KeyEvent{Key::character, 'k'}) == Direction::up);
  CHECK(direction_of(KeyEvent{Key::character, 'l'}) == Direction::right);
  CHECK(action_of(KeyEvent{Key::character, 'l'}, Phase::play).kind == ActionKind::move);
  CHECK(action_of(KeyEvent{Key::character, 'l'}, Phase::shop).kind == ActionKind::buy);  // the shop's life
}

TEST_CASE("SGR mouse reports decode to the pointer's cell", "[client][keys][mouse]") {
  KeyDecoder d;
  CHECK(kMouseOn == "\x1b[?1003h\x1b[?1006h\x1b[?1004h");  // any motion, SGR form, focus reports
  auto ev = d.feed("\x1b[<35;10;5M\x1b[<0;1;1M\x1b[<0;120;40m\x1b[<64;3;3M");
  REQUIRE(ev.size() == 4);
  CHECK(ev[0].key == Key::mouse);
  CHECK(ev[0].motion);
  CHECK(ev[0].button == 3);  // motion without a button
  CHECK(ev[0].col == 9);
  CHECK(ev[0].row == 4);
  CHECK_FALSE(ev[1].motion);
  CHECK(ev[1].button == 0);
  CHECK(ev[1].action == KeyAction::press);
  CHECK(ev[1].col == 0);
  CHECK(ev[2].action == KeyAction::release);
  CHECK(ev[2].col == 119);
  CHECK(ev[2].row == 39);
  CHECK(ev[3].button == 64);  // wheel
  CHECK(action_of(ev[0], Phase::play).kind == ActionKind::pointer);
  SECTION("split across reads") {
    CHECK(d.feed("\x1b[<32;4").empty());
    auto rest = d.feed(";7M");
    REQUIRE(rest.size() == 1);
    CHECK(rest[0].col == 3);
    CHECK(rest[0].row == 6);
  }
  SECTION("malformed reports are dropped, keys after them still decode") {
    auto bad = d.feed("\x1b[<1;2M\x1b[<0;0;5Mw");
    REQUIRE(bad.size() == 1);
    CHECK(bad[0].ch == 'w');
  }
}

TEST_CASE("mouse steering thrusts toward the pointer on each axis", "[client][keys][mouse]") {
  CHECK(steer_toward(100, 100, 300, 100, 5) == Steer{1, 0});
  CHECK(steer_toward(100, 100, 40, 160, 5) == Steer{-1, 1});
  CHECK(steer_toward(100, 100, 103, 96, 5) == Steer{0, 0});  // on the ball: still
  CHECK(steer_toward(100, 100, std::nan(""), 300, 5) == Steer{0, 1});
}

TEST_CASE("chat, follow and typed case", "[client][keys]") {
  KeyDecoder d;
  auto ev = d.feed("tT\t\x7f");
  REQUIRE(ev.size() == 4);
  CHECK(action_of(ev[0], Phase::play).kind == ActionKind::chat);
  CHECK(ev[1].text == 'T');
  CHECK(ev[1].ch == 't');
  CHECK(action_of(ev[2], Phase::play).kind == ActionKind::follow);
  CHECK(ev[3].key == Key::backspace);
  KeyDecoder k;
  auto shifted = k.feed("\x1b[104;2u");  // kitty: shift+h
  REQUIRE(shifted.size() == 1);
  CHECK(shifted[0].text == 'H');
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

// Issue 31 (a terminal at the other end of ssh may be anything): the flags are pushed
// only where the kitty query is answered before DA1, which every terminal answers.
TEST_CASE("kitty flags wait for the terminal's answer", "[client][keys][ssh]") {
  const std::string init = enter_bytes(true, false);
  CHECK(init.find(kKittyQuery) != std::string::npos);
  CHECK(init.find(kDeviceQuery) > init.find(kKittyQuery));
  CHECK(init.find("\x1b[>") == std::string::npos);  // no push before an answer
  CHECK(enter_bytes(false, false).find(kKittyQuery) == std::string::npos);
  CHECK(enter_bytes(false, true).find(kMouseOn) != std::string::npos);

  KeyDecoder plain;  // tmux, xterm, PuTTY: DA1 only, and no key comes of it
  CHECK(plain.feed("\x1b[?62;22c").empty());
  CHECK(plain.device_answered());
  CHECK_FALSE(plain.kitty_answered());
  CHECK(plain.feed("\x1b[?0u").empty());  // too late: after DA1
  CHECK_FALSE(plain.kitty_answered());
  CHECK(plain.feed("\x1b[A").at(0) == KeyEvent{Key::up});

  KeyDecoder kitty;  // answers both, in order; after our push, again with the flags
  CHECK(kitty.feed("\x1b[?0u\x1b[?1;2c").empty());
  CHECK(kitty.kitty_answered());
  CHECK_FALSE(kitty.kitty_supported());
  CHECK(kitty.feed("\x1b[?11u").empty());
  CHECK(kitty.kitty_supported());

  KeyDecoder split;  // an answer cut in two reads
  CHECK(split.feed("\x1b[?0").empty());
  CHECK(split.feed("u").empty());
  CHECK(split.kitty_answered());
}
