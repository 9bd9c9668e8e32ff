// Room codes: 5 letters a person can read out and type (no I, L, O: they look like 1
// and 0), drawn from a generator of their own, seeded once, so that making a room never
// touches any match's random generator (a match's seed and inputs alone replay it).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace fts::server {

inline constexpr std::string_view kRoomCodeAlphabet = "ABCDEFGHJKMNPQRSTUVWXYZ";
inline constexpr std::size_t kRoomCodeLength = 5;

// Upper-cases a typed code; nullopt if it is not 5 letters of the alphabet.
std::optional<std::string> normalize_room_code(std::string_view typed);

class RoomCodes {
 public:
  explicit RoomCodes(std::uint64_t seed) : state_(seed) {}
  // A code for which taken(code) is false; draws again on a collision (at most
  // max_draws times, then nullopt: with 23^5 = 6.4 million codes and at most a few
  // hundred rooms that means the generator is broken).
  std::optional<std::string> next(const std::function<bool(const std::string&)>& taken, int max_draws = 64);
  std::uint64_t draws() const { return draws_; }

 private:
  std::uint64_t next_u64();  // splitmix64
  std::uint64_t state_;
  std::uint64_t draws_ = 0;
};

}  // namespace fts::server
