// The client's one clock: milliseconds of the monotonic clock (steady_clock). Everything
// in net/ and predict/ takes times passed in; the loops that drive them (the game, the
// replay, --forget-me) read them here.
#pragma once

#include <chrono>
#include <cstdint>

namespace fts::client {

inline std::uint64_t now_ms() {
  using namespace std::chrono;
  return static_cast<std::uint64_t>(duration_cast<milliseconds>(steady_clock::now().time_since_epoch()).count());
}

}  // namespace fts::client
