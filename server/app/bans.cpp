#include "app/bans.hpp"

#include "fts/protocol/limits.hpp"

namespace fts::server {

bool Bans::drops(std::string_view from, std::uint64_t now_ms) {
  if (until_.empty()) return false;
  auto it = until_.find(protocol::host_of(from));
  if (it == until_.end() || now_ms >= it->second) return false;
  ++dropped_;
  return true;
}

void Bans::expire(std::uint64_t now_ms) {
  if (!until_.empty()) std::erase_if(until_, [&](const auto& kv) { return now_ms >= kv.second; });
}

}  // namespace fts::server
