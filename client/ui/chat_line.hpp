// The chat line being typed (after `t`): it takes every key. Enter sends it, Esc or
// Ctrl-C cancels, Backspace erases; printable keys add up to max_chars.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "term/keys.hpp"
#include "ui/view.hpp"

namespace fts::client {

// Edits view.chat_draft (closing view.chat_open on Enter, Esc or Ctrl-C); on Enter, the
// line to send, cleaned (possibly empty: nothing to send).
std::optional<std::string> edit_chat_line(ViewState& view, const KeyEvent& e, std::size_t max_chars);

}  // namespace fts::client
