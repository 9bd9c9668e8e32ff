#include "term/io.hpp"

#include <unistd.h>

#include "term/hangup.hpp"
#include "term/terminal.hpp"
#include "ui/render.hpp"

namespace fts::client::term {

std::vector<KeyEvent> KeyReader::read(std::uint64_t now_ms) {
  char buf[256];
  std::vector<KeyEvent> events;
  for (;;) {
    const ssize_t n = ::read(STDIN_FILENO, buf, sizeof buf);
    if (n <= 0) break;
    auto more = decoder_.feed(std::string_view(buf, static_cast<std::size_t>(n)));
    events.insert(events.end(), more.begin(), more.end());
    last_key_ms_ = now_ms;
  }
  if (decoder_.pending() && now_ms - last_key_ms_ > kPauseMs) {
    auto more = decoder_.flush();
    events.insert(events.end(), more.begin(), more.end());
  }
  if (decoder_.kitty_answered() && !kitty_pushed_) {
    term::push_kitty();
    kitty_pushed_ = true;
  }
  if (hung_up(STDIN_FILENO)) term::note_hangup();
  return events;
}

TerminalSize Painter::size() {
  const TerminalSize now = term::size();
  if (term::take_resized() || now.cols != size_.cols || now.rows != size_.rows) clear_ = true;
  size_ = now;
  return size_;
}

void Painter::paint(const Screen& screen, bool color) {
  std::string out;
  if (clear_) {
    out += "\x1b[0m\x1b[2J";
    last_rows_.clear();
    clear_ = false;
  }
  out += repaint(screen, last_rows_, color);
  if (!out.empty()) write_all(out);
}

}  // namespace fts::client::term
