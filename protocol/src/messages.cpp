// Message helpers that are not wire fields (those are in the field tables).
#include <string>

#include "fts/protocol/messages.hpp"

namespace fts::protocol {

std::string name_problem(const std::string& name) {
  if (name.empty()) return "a name needs at least one character";
  if (name.size() > kMaxNameBytes)
    return "a name has at most " + std::to_string(kMaxNameBytes) + " characters, this one " +
           std::to_string(name.size());
  for (unsigned char c : name)
    if (c < 0x20 || c > 0x7E) return "a name may only hold printable ASCII characters (no control codes, no accents)";
  return "";
}

std::uint32_t Welcome::tick_rate_hz() const {
  const double hz = match.tick_rate_hz;
  if (!(hz >= 1.0 && hz <= 10000.0) || static_cast<double>(static_cast<std::uint32_t>(hz)) != hz) return 100;
  return static_cast<std::uint32_t>(hz);
}

}  // namespace fts::protocol
