#include <catch2/catch.hpp>

#include "seed_situation.hpp"
#include "ui/render.hpp"
#include "ui/sanitize.hpp"

using namespace fts::client;

TEST_CASE("network text loses control and escape characters", "[client][sanitize]") {
  CHECK(sanitize("ann") == "ann");
  CHECK(sanitize("\x1b[2J\x1b]0;pwned\x07x") == "[2J]0;pwnedx");
  CHECK(sanitize("a\rb\nc\td\x7f") == "abcd");
  CHECK(sanitize("caf\xc3\xa9") == "caf?");          // non-ASCII: one placeholder
  CHECK(sanitize("\xc2\x9b" "31m") == "?31m");        // C1 CSI cannot pass
  CHECK(sanitize("\xff\xfe") == "??");                // invalid UTF-8
  CHECK(sanitize(std::string(100, 'x'), 16).size() == 16);
  CHECK(sanitize(std::string("a\0b", 3)) == "ab");
}

TEST_CASE("a name carrying escape sequences reaches the screen clean", "[client][sanitize]") {
  auto snap = fts::client::test::seed_snapshot(fts::protocol::Phase::play);
  auto evil = fts::client::test::seed_player();
  evil.id = 2;
  evil.name = "\x1b[31mEVIL\x1b[0m\x1b]2;title\x07";
  snap.players.push_back(evil);
  ViewState view;
  view.my_player_id = 1;
  const Screen screen = render(snap, snap, 0, {120, 30}, view);
  for (const auto& line : screen.lines()) {
    for (char c : line) CHECK((c >= 0x20 && c < 0x7f));
  }
  bool legend = false;  // 16 characters at most, in the legend
  for (const auto& line : screen.lines()) legend = legend || line.find("[31mEVIL[0m]2;ti") != std::string::npos;
  CHECK(legend);
  // The ANSI output has exactly the escapes we made: none from the name.
  view.color = false;
  const std::string bytes = to_ansi(render(snap, snap, 0, {120, 30}, view), false);
  CHECK(bytes.find("\x1b[31m") == std::string::npos);
  CHECK(bytes.find("\x1b]") == std::string::npos);
  CHECK(bytes.find('\x07') == std::string::npos);
  // The shop's ready list uses the same names.
  snap.phase = fts::protocol::Phase::shop;
  const std::string shop = to_ansi(render(snap, snap, 0, {120, 40}, view), false);
  CHECK(shop.find("\x1b[31m") == std::string::npos);
}

// Issue 31: over ssh the name comes from the key's comment or a prompt, cleaned as names
// from the network are.
TEST_CASE("a player's name from a key comment or a prompt", "[client][sanitize][ssh]") {
  CHECK(player_name("alice") == "alice");
  CHECK(player_name("  bob@laptop \r\n") == "bob@laptop");
  CHECK(player_name("\x1b[31mred") == "[31mred");
  CHECK(player_name("Zo\xc3\xab") == "Zo?");
  CHECK(player_name("a very long name indeed, longer") == "a very long name");
  CHECK(player_name("fifteen chars  x") == "fifteen chars  x");
  CHECK(player_name("fifteen chars   xyz") == "fifteen chars");  // clipped, then trimmed
  CHECK(player_name("   ").empty());
  CHECK(player_name("\x01\x02").empty());
}
