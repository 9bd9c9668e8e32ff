#include "ui/forget.hpp"

#include <cctype>

#include "fts/protocol/codes.hpp"
#include "ui/hud.hpp"
#include "ui/sanitize.hpp"

namespace fts::client {

std::string forget_prompt(const std::string& server, const std::string& fingerprint, const std::string& identity_path) {
  return "This erases your profile on " + sanitize(server, 80) + ": every record of identity " +
         sanitize(fingerprint, 32) + " (matches, best level, your place on the leaderboard). It cannot be undone.\n" +
         "Your identity file " + sanitize(identity_path, 200) + " is kept.\n" + "Type yes to erase: ";
}

bool forget_confirmed(std::string_view line) {
  while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front()))) line.remove_prefix(1);
  while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.remove_suffix(1);
  if (line.size() != 3) return false;
  for (std::size_t i = 0; i < 3; ++i)
    if (std::tolower(static_cast<unsigned char>(line[i])) != "yes"[i]) return false;
  return true;
}

ForgetOutcome forget_outcome(const protocol::Result& result, const std::string& identity_path) {
  ForgetOutcome o;
  if (result.ok) {
    o.erased = true;
    const std::string msg = sanitize(result.message, 200);
    o.text = (msg.empty() ? std::string("your profile is erased") : msg) + ".\nYour identity file " +
             sanitize(identity_path, 200) +
             " is kept: play with it again and this server starts a new profile; delete it to be someone new.";
    return o;
  }
  o.text = "not erased: " + refusal_text(result.code, result.message, 0, nullptr) + ".";
  return o;
}

}  // namespace fts::client
