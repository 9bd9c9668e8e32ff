#include "ui/chat_line.hpp"

#include "ui/sanitize.hpp"

namespace fts::client {

std::optional<std::string> edit_chat_line(ViewState& view, const KeyEvent& e, std::size_t max_chars) {
  if (e.action == KeyAction::release || is_report(e)) return std::nullopt;
  if (e.key == Key::escape || e.key == Key::ctrl_c || e.key == Key::enter) {
    std::optional<std::string> line;
    if (e.key == Key::enter) line = sanitize(view.chat_draft, max_chars);
    view.chat_open = false;
    view.chat_draft.clear();
    return line;
  }
  if (e.key == Key::backspace) {
    if (!view.chat_draft.empty()) view.chat_draft.pop_back();
  } else if (view.chat_draft.size() < max_chars) {
    if (e.key == Key::space) view.chat_draft += ' ';
    else if (e.key == Key::character && e.text != 0) view.chat_draft += e.text;
  }
  return std::nullopt;
}

LogLine chat_log_line(const protocol::Chat& c, std::uint64_t now_ms, std::size_t max_chars) {
  const std::string name = c.from == 0 ? std::string("host") : sanitize(c.name, 16);
  return LogLine{name + ": " + sanitize(c.text, max_chars), now_ms, c.from, name.size() + 1, c.from == 0};
}

}  // namespace fts::client
