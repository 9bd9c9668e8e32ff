#include "ui/sanitize.hpp"

#include <algorithm>

namespace fts::client {

std::string sanitize(std::string_view text, std::size_t max_chars) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && out.size() < max_chars;) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b < 0x80) {
      if (b >= 0x20 && b != 0x7f) out += static_cast<char>(b);
      ++i;
      continue;
    }
    // Skip one UTF-8 sequence (or one stray byte) and show a placeholder.
    std::size_t len = 1;
    if ((b & 0xE0) == 0xC0) len = 2;
    else if ((b & 0xF0) == 0xE0) len = 3;
    else if ((b & 0xF8) == 0xF0) len = 4;
    std::size_t j = i + 1;
    while (j < text.size() && j < i + len && (static_cast<unsigned char>(text[j]) & 0xC0) == 0x80) ++j;
    out += '?';
    i = j;
  }
  return out;
}

std::string player_name(std::string_view text, std::size_t max_chars) {
  std::string out = sanitize(text);
  const auto trim = [&out] {
    out.erase(0, std::min(out.find_first_not_of(' '), out.size()));
    out.erase(out.find_last_not_of(' ') + 1);
  };
  trim();
  if (out.size() > max_chars) out.resize(max_chars);
  trim();
  return out;
}

}  // namespace fts::client
