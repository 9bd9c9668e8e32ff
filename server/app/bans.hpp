// The host's bans (the console's `ban`): hosts (addresses without their port) whose
// datagrams are dropped unanswered until a time; a ban costs the server a map lookup.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace fts::server {

class Bans {
 public:
  void ban(std::string_view host, std::uint64_t until_ms) { until_[std::string(host)] = until_ms; }
  // Whether a datagram from `from` (host:port) is dropped now; counted when it is.
  bool drops(std::string_view from, std::uint64_t now_ms);
  // Forgets the bans that are over.
  void expire(std::uint64_t now_ms);
  std::size_t size() const { return until_.size(); }
  std::uint64_t dropped_datagrams() const { return dropped_; }

 private:
  std::map<std::string, std::uint64_t, std::less<>> until_;  // host -> until (ms)
  std::uint64_t dropped_ = 0;
};

}  // namespace fts::server
