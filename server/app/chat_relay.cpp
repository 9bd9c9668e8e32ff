#include "app/chat_relay.hpp"

#include <algorithm>

namespace fts::server {

std::string ChatRelay::clean(std::string_view text, std::size_t max_chars) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && out.size() < max_chars; ++i) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b >= 0x80) {
      // One '?' per UTF-8 sequence (continuation bytes are skipped).
      if ((b & 0xC0) != 0x80) out += '?';
      continue;
    }
    const char c = (b == '\t') ? ' ' : static_cast<char>(b);
    if (c < 0x20 || c == 0x7f) continue;
    if (c == ' ' && (out.empty() || out.back() == ' ')) continue;
    out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

ChatVerdict ChatRelay::accept(std::uint32_t player_id, std::string_view text, std::uint64_t now_ms) {
  std::string line = clean(text, limits_.max_chars);
  if (line.empty()) return {false, protocol::ResultCode::empty, {}};
  auto it = buckets_.find(player_id);
  if (it == buckets_.end()) {
    if (buckets_.size() >= limits_.max_tracked) {
      // Forget the players whose bucket has filled up again: they lose nothing.
      std::erase_if(buckets_, [&](const auto& kv) {
        return kv.second.tokens + static_cast<double>(now_ms - kv.second.at_ms) / static_cast<double>(limits_.refill_ms) >=
               limits_.burst_lines;
      });
    }
    it = buckets_.emplace(player_id, Bucket{limits_.burst_lines, now_ms}).first;
  }
  Bucket& b = it->second;
  if (now_ms > b.at_ms && limits_.refill_ms > 0)
    b.tokens = std::min(limits_.burst_lines, b.tokens + static_cast<double>(now_ms - b.at_ms) / static_cast<double>(limits_.refill_ms));
  b.at_ms = std::max(b.at_ms, now_ms);
  if (b.tokens < 1) return {false, protocol::ResultCode::rate, {}};
  b.tokens -= 1;
  return {true, protocol::ResultCode::ok, std::move(line)};
}

}  // namespace fts::server
