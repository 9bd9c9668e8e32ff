#include <algorithm>
#include <catch2/catch.hpp>

#include "../../support/seed_shop_lines.hpp"
#include "seed_situation.hpp"
#include "ui/hud.hpp"
#include "ui/render.hpp"

using namespace fts::client;
using fts::protocol::Phase;

namespace {

bool screen_has(const Screen& s, const std::string& text) {
  for (const auto& line : s.lines())
    if (line.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("the shop screen of the seed's situation gives the seed's lines", "[client][shop]") {
  const std::vector<std::string>& seed = fts::test::seed_shop_lines();
  CHECK(shop_screen_lines(fts::client::test::seed_player(), 3) == seed);

  ViewState view;
  view.my_player_id = 1;
  SECTION("a tall terminal shows every line in the slide's order, groups spaced") {
    const Screen s = render(fts::client::test::seed_snapshot(Phase::shop), fts::client::test::seed_snapshot(Phase::shop), 0, {90, 50}, view);
    const auto lines = s.lines();
    std::size_t row = 0;
    for (const auto& want : seed) {
      auto it = std::find_if(lines.begin() + static_cast<long>(row), lines.end(),
                             [&](const std::string& l) { return l.find(want) != std::string::npos; });
      INFO(want);
      REQUIRE(it != lines.end());
      row = static_cast<std::size_t>(it - lines.begin()) + 1;
    }
    CHECK(screen_has(s, "Ready: ann (shopping)"));
    CHECK(screen_has(s, "Buy: m s a r l x b   Ready: Enter   Chat: t   Quit: q"));
  }
  SECTION("a 24-row terminal still shows every price") {
    const Screen s = render(fts::client::test::seed_snapshot(Phase::shop), fts::client::test::seed_snapshot(Phase::shop), 0, {80, 24}, view);
    for (std::size_t i = 3; i < seed.size(); ++i) {
      INFO(seed[i]);
      CHECK(screen_has(s, seed[i]));
    }
  }
  SECTION("a purchase's result and who is ready are shown") {
    auto snap = fts::client::test::seed_snapshot(Phase::shop);
    auto bob = fts::client::test::seed_player();
    bob.id = 2;
    bob.name = "bob";
    bob.ready = true;
    snap.players.push_back(bob);
    snap.players[0].coins = 251;
    snap.players[0].mass = 41;
    snap.players[0].prices[0] = 36;
    view.shop_result = "You bought mass for 35 coins.";
    const Screen s = render(snap, snap, 0, {90, 50}, view);
    CHECK(screen_has(s, "Coins: 251"));
    CHECK(screen_has(s, "Current Mass: 41"));
    CHECK(screen_has(s, "To increase Mass, press 'm' (36 coins)"));
    CHECK(screen_has(s, "You bought mass for 35 coins."));
    CHECK(screen_has(s, "Ready: ann (shopping), bob (ready)"));
  }
  SECTION("owned rockets and bank drop their offers") {
    auto p = fts::client::test::seed_player();
    p.weapon = fts::protocol::Weapon::rockets;
    p.bank = true;
    const auto lines = shop_screen_lines(p, 3);
    CHECK(std::find(lines.begin(), lines.end(), "Current Weapon: ROCKETS.") != lines.end());
    CHECK(std::find(lines.begin(), lines.end(), "Bank Purchased: True") != lines.end());
    CHECK(std::none_of(lines.begin(), lines.end(), [](const std::string& l) { return l.find("press 'r'") != std::string::npos; }));
  }
}

// Issue 26 (8): at 80x40 the spaced slide filled the rows and the standings were left
// out, although dropping its blank lines left room for them.
TEST_CASE("the shop shows the standings whenever the slide can leave room for them", "[client][shop]") {
  const char* const names[] = {"ann", "bob", "cleo", "dora", "eve", "fay", "gus", "hiro"};
  const struct {
    std::size_t players;
    TerminalSize size;
  } cases[] = {{2, {80, 30}}, {2, {80, 40}}, {8, {80, 45}}, {2, {100, 40}}, {8, {110, 45}}};
  for (const auto& c : cases) {
    INFO(c.players << " players at " << c.size.cols << "x" << c.size.rows);
    auto snap = fts::client::test::seed_snapshot(Phase::shop);
    snap.players.clear();
    for (std::size_t i = 0; i < c.players; ++i) {
      auto p = fts::client::test::seed_player();
      p.id = static_cast<std::uint32_t>(i + 1);
      p.name = names[i];
      snap.players.push_back(p);
    }
    ViewState view;
    view.my_player_id = 1;
    const Screen s = render(snap, snap, 0, c.size, view);
    CHECK(screen_has(s, "Standings after level 3"));
    CHECK(screen_has(s, "  1 ann*"));
    CHECK(screen_has(s, " " + std::to_string(c.players) + " " + names[c.players - 1]));
    // Every offer and what it does stays on the slide.
    for (const auto& line : shop_screen_lines(snap.players[0], 3)) {
      if (line.rfind("Level:", 0) == 0 || line.rfind("Coins:", 0) == 0 || line.rfind("Lives:", 0) == 0) continue;
      INFO(line);
      CHECK(screen_has(s, line));
    }
  }
}
