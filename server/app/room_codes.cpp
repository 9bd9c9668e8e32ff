#include "app/room_codes.hpp"

namespace fts::server {

std::optional<std::string> normalize_room_code(std::string_view typed) {
  if (typed.size() != kRoomCodeLength) return std::nullopt;
  std::string code;
  for (char c : typed) {
    const char up = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
    if (kRoomCodeAlphabet.find(up) == std::string_view::npos) return std::nullopt;
    code += up;
  }
  return code;
}

std::uint64_t RoomCodes::next_u64() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::optional<std::string> RoomCodes::next(const std::function<bool(const std::string&)>& taken, int max_draws) {
  for (int i = 0; i < max_draws; ++i) {
    ++draws_;
    std::uint64_t bits = next_u64();
    std::string code;
    for (std::size_t k = 0; k < kRoomCodeLength; ++k) {
      code += kRoomCodeAlphabet[bits % kRoomCodeAlphabet.size()];
      bits /= kRoomCodeAlphabet.size();
    }
    if (!taken(code)) return code;
  }
  return std::nullopt;
}

}  // namespace fts::server
