// 80x24 is the primary size (an ssh terminal) and 120x40 the roomy one (issue 37): the
// start screen breaks no word, the footers fit whole, the field takes the rows, the side
// panel shows where the docs say, and the shop leaves the log its rows.
#include <catch2/catch.hpp>

#include <sstream>

#include "seed_situation.hpp"
#include "ui/panel.hpp"
#include "ui/render.hpp"
#include "ui/start_screen.hpp"

using namespace fts::client;
using fts::protocol::BallKind;
using fts::protocol::BallState;
using fts::protocol::Phase;
using fts::protocol::Snapshot;

namespace {

Snapshot players(int n, Phase phase) {
  Snapshot s = fts::client::test::seed_snapshot(phase);
  s.players.clear();
  for (int i = 0; i < n; ++i) {
    auto p = fts::client::test::seed_player();
    p.id = static_cast<std::uint32_t>(i + 1);
    p.name = i == 0 ? "ann" : "player" + std::to_string(i + 1);
    s.players.push_back(p);
  }
  return s;
}

std::string squeezed(const std::string& text) {
  std::istringstream in(text);
  std::string out, w;
  while (in >> w) out += (out.empty() ? "" : " ") + w;
  return out;
}

}  // namespace

TEST_CASE("80x24: the start screen wraps at spaces", "[client][layout]") {
  const std::string wide = start_menu_text(200);
  for (const int cols : {80, 60}) {
    INFO(cols);
    const std::string text = start_menu_text(cols);
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) CHECK(static_cast<int>(line.size()) <= cols);
    // The same words in the same order: none cut in two.
    CHECK(squeezed(text) == squeezed(wide));
  }
  CHECK(start_menu_text(80).find("level, phase).") == std::string::npos);  // 87 characters: wrapped
  CHECK(start_menu_text(80).find("phase).") != std::string::npos);
}

TEST_CASE("80x24: every footer fits whole", "[client][layout]") {
  for (const Phase phase : {Phase::lobby, Phase::play, Phase::shop, Phase::over}) {
    for (const int variant : {0, 1, 2}) {  // 0: playing, mouse steering; 1: out of lives; 2: watching
      Snapshot s = players(3, phase);
      s.players[1].name = "sixteen_letters_";
      ViewState v = fts::client::test::plain_view();
      v.mouse_steering = variant == 0;
      if (variant == 1) s.players[0].lives = 0, s.players[0].alive = false;
      if (variant == 2) v.my_player_id = 99;
      const std::string footer = footer_text(s, v, 80);
      INFO(static_cast<int>(phase) << "/" << variant << ": " << footer);
      CHECK(footer.size() <= 80);
      CHECK(footer.find("Quit: q") != std::string::npos);
      if (phase == Phase::play && variant == 0) CHECK(footer.find("(mouse steering)") != std::string::npos);
      if (variant == 1 && (phase == Phase::play || phase == Phase::shop)) CHECK(footer.find("Out") != std::string::npos);
      const Screen screen = render(s, s, 0, {80, 24}, v);
      CHECK(screen.line(23).find(footer) == 0);
    }
  }
}

TEST_CASE("80x24: the field takes the rows between the legend and the log", "[client][layout]") {
  for (const int n : {1, 2, 4, 8}) {
    INFO(n << " players");
    const Snapshot s = players(n, Phase::play);
    const FrameLayout L = frame_layout({80, 24}, fts::client::test::plain_view(), s);
    CHECK_FALSE(L.side);
    // Frame just under the legend, just over the log: no empty row between them.
    CHECK(L.arena.row0 - 1 == L.legend_row0 + L.legend_rows);
    CHECK(L.arena.row0 + L.arena.rows + 1 == L.log_row0);
    CHECK(L.log_row0 + L.log_rows == L.footer_row);
    CHECK(L.log_rows >= 2);
    // Wider than the 45 columns it had beside the panel.
    CHECK(L.arena.cols >= (n <= 4 ? 55 : 50));
  }
}

TEST_CASE("100x30: the side panel shows, as the docs say", "[client][layout]") {
  for (const int n : {1, 2, 4, 8}) {
    INFO(n << " players");
    for (const Phase phase : {Phase::lobby, Phase::play, Phase::shop}) {
      const Snapshot s = players(n, phase);
      const FrameLayout L = frame_layout({100, 30}, fts::client::test::plain_view(), s);
      CHECK(L.side);
      CHECK(L.log_rows >= 10);
    }
  }
}

TEST_CASE("the shop's log follows the chat at 120x40 and keeps rows at 80x24", "[client][layout][shop]") {
  const Snapshot s = players(3, Phase::shop);
  ViewState v = fts::client::test::plain_view();
  v.now_ms = 100'000;
  for (int i = 0; i < 8; ++i) v.messages.push_back(LogLine{"bob: chat line " + std::to_string(i), 90'000 + 1000u * i});
  std::string text;
  for (const auto& l : render(s, s, 0, {120, 40}, v).lines()) text += l + "\n";
  for (int i = 3; i < 8; ++i) CHECK(text.find("chat line " + std::to_string(i)) != std::string::npos);
  // 80x24: the slide needs most rows, the log still shows the newest line.
  text.clear();
  for (const auto& l : render(s, s, 0, {80, 24}, v).lines()) text += l + "\n";
  CHECK(text.find("chat line 7") != std::string::npos);
}

TEST_CASE("a purchase's result goes after a while", "[client][shop]") {
  const Snapshot s = players(1, Phase::shop);
  ViewState v = fts::client::test::plain_view();
  v.shop_result = "Cannot buy: not enough coins.";
  v.shop_result_ms = 50'000;
  const auto shown = [&](std::uint64_t now) {
    v.now_ms = now;
    for (const TerminalSize size : {TerminalSize{80, 24}, TerminalSize{120, 40}})
      for (const auto& l : render(s, s, 0, size, v).lines())
        if (l.find("Cannot buy") != std::string::npos) return true;
    return false;
  };
  CHECK(shown(50'000));
  CHECK(shown(50'000 + kShopResultShowMs - 1));
  CHECK_FALSE(shown(50'000 + kShopResultShowMs));
}
