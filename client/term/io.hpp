// The terminal's two streams as the game loop uses them: keys read from stdin (a lone
// ESC is decided after a pause), and frames painted to stdout (only what changed).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "term/keys.hpp"
#include "ui/screen.hpp"

namespace fts::client::term {

class KeyReader {
 public:
  // Every key read from stdin since the last call (non-blocking), decoded; an escape
  // sequence left incomplete for kPauseMs is taken as typed. Pushes the kitty flags once
  // the terminal has answered the query, and notes a terminal that hung up.
  std::vector<KeyEvent> read(std::uint64_t now_ms);
  static constexpr std::uint64_t kPauseMs = 50;
  // When the terminal last sent something (a key, the pointer; 0: never).
  std::uint64_t last_key_ms() const { return last_key_ms_; }

 private:
  KeyDecoder decoder_;
  std::uint64_t last_key_ms_ = 0;
  bool kitty_pushed_ = false;
};

class Painter {
 public:
  // Writes the rows of the frame that differ from the last one's (all of them after a
  // resize, which clears first): a ball moving a dot rewrites its rows, not the screen.
  void paint(const Screen& screen, bool color);
  // The size to draw the next frame at (noting a resize).
  TerminalSize size();

 private:
  TerminalSize size_{0, 0};
  bool clear_ = true;
  std::vector<std::string> last_rows_;
};

}  // namespace fts::client::term
