// Text that came over the network is hostile: before it reaches the terminal, every
// control character (C0, DEL, C1) and escape sequence introducer is removed and anything
// outside printable ASCII is replaced, so a name cannot move the cursor or recolour.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace fts::client {

// Printable ASCII only: control bytes and DEL are dropped, each non-ASCII UTF-8 sequence
// (C1 controls included) becomes one '?'; the result is at most max_chars long.
std::string sanitize(std::string_view text, std::size_t max_chars = 64);

// A player's name from text a person typed or a host wrote (an ssh key's comment, a
// name file): sanitized, spaces trimmed at both ends, at most max_chars long; "" when
// nothing is left.
std::string player_name(std::string_view text, std::size_t max_chars = 16);

}  // namespace fts::client
