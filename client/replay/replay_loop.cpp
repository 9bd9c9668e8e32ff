#include "replay/replay_loop.hpp"

#include <chrono>
#include <fstream>
#include <thread>

#include "replay/replay.hpp"
#include "net/clock.hpp"
#include "term/io.hpp"
#include "term/terminal.hpp"
#include "ui/hud.hpp"
#include "ui/panel.hpp"
#include "ui/render.hpp"
#include "ui/sanitize.hpp"

namespace fts::client {

namespace {

void note(ViewState& view, std::string text, std::uint64_t now) {
  view.messages.push_back(LogLine{std::move(text), now});
  if (view.messages.size() > kLogKeep) view.messages.erase(view.messages.begin());
}

}  // namespace

int run_replay(const std::string& path, bool kitty, bool fine, std::string& message) {
  auto loaded = load_history(path);
  if (auto* err = std::get_if<std::string>(&loaded)) {
    // The reason quotes the file (its version string, the bytes JSON stopped at): a
    // record from elsewhere must not reach the terminal raw (issue 30).
    message = sanitize(path, 200) + ": " + sanitize(*err, 300);
    return 1;
  }
  Replay replay(std::move(std::get<Tape>(loaded)));
  if (!term::enter(kitty, false)) {
    message = "needs a terminal (stdin and stdout must be a tty)";
    return 1;
  }
  ViewState view;
  view.color = color_wanted(std::getenv("NO_COLOR"), std::getenv("TERM"));
  view.fine = fine;
  view.arena_width_u = replay.tape().config.arena_width_u;
  view.arena_height_u = replay.tape().config.arena_height_u;
  view.tick_rate_hz = replay.tape().config.tick_rate_hz;
  term::KeyReader keys;
  term::Painter painter;
  std::uint64_t last = now_ms();
  note(view, "Replaying " + sanitize(path, 60) + " (" + replay.tape().format + ", seed " + std::to_string(replay.tape().seed) + ").", last);
  bool mismatch_told = false;
  for (;;) {
    if (term::stop_signal() != 0) break;
    const std::uint64_t now = now_ms();
    bool quit = false;
    for (const KeyEvent& e : keys.read(now)) {
      if (e.action == KeyAction::release || is_report(e)) continue;
      const char c = e.key == Key::character ? e.text : 0;
      if (e.key == Key::ctrl_c || c == 'q' || c == 'Q') quit = true;
      else if (e.key == Key::space) replay.toggle_pause();
      else if (c == '+' || c == '=') replay.faster();
      else if (c == '-' || c == '_') replay.slower();
      else if (c == 'n') replay.seek_level(replay.state().level + 1);
      else if (c == 'p') replay.seek_level(replay.state().level - 1);
      else if (c >= '1' && c <= '9') replay.seek_level(c - '0');
      else if (c == 'e') replay.run_to(replay.tape().last_tick);
      else if (e.key == Key::tab) {
        const protocol::Snapshot s = replay.snapshot();
        view.follow_id = next_follow(s, view.follow_id, 0);
      }
    }
    if (quit) break;
    replay.advance(now - last);
    last = now;
    protocol::Snapshot snap = replay.snapshot();
    replay_log(replay, snap, view, now);
    if (!replay.mismatch().empty() && !mismatch_told) {
      note(view, "The record differs from this build's match: " + replay.mismatch(), now);
      mismatch_told = true;
    }
    // The followed player's view: its coins in the HUD, its ball as '@'.
    view.follow_id = followed(snap, view);
    view.my_player_id = view.follow_id;
    view.now_ms = now;
    const TerminalSize size = painter.size();
    view.replay_footer = replay_footer(replay, size.cols);
    painter.paint(render(snap, snap, 0, size, view), view.color);
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
  }
  term::leave();
  return 0;
}

}  // namespace fts::client
