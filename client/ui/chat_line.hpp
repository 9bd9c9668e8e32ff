// The chat line being typed (after `t`): it takes every key. Enter sends it, Esc or
// Ctrl-C cancels, Backspace erases; printable keys add up to max_chars.
// And a chat line heard, as the message log shows it.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "fts/protocol/messages.hpp"
#include "term/keys.hpp"
#include "ui/view.hpp"

namespace fts::client {

// Edits view.chat_draft (closing view.chat_open on Enter, Esc or Ctrl-C); on Enter, the
// line to send, cleaned (possibly empty: nothing to send).
std::optional<std::string> edit_chat_line(ViewState& view, const KeyEvent& e, std::size_t max_chars);

// A chat line heard (protocol Chat) as the message log shows it: "name: text", the name
// coloured (from 0: "host", in the title style). Name and text are sanitised here,
// whatever the server and the decoder let through.
LogLine chat_log_line(const protocol::Chat& c, std::uint64_t now_ms, std::size_t max_chars);

}  // namespace fts::client
