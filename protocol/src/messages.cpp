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

}  // namespace fts::protocol
