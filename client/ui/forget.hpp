// fts-client --forget-me (issue 41, PROTOCOL.md 4.7c): the words around the erasure of the
// player's profile: the question asked first, the answer that confirms it, what the
// server's result means. Pure; forget_me.cpp does the connection.
#pragma once

#include <string>
#include <string_view>

#include "fts/protocol/messages.hpp"

namespace fts::client {

// The question before anything is sent.
std::string forget_prompt(const std::string& server, const std::string& fingerprint, const std::string& identity_path);

// Whether a typed line confirms: "yes" (any case, spaces around it); anything else does not.
bool forget_confirmed(std::string_view line);

// What the player reads after the server's result, and whether it erased (or will).
struct ForgetOutcome {
  bool erased = false;
  std::string text;
};
ForgetOutcome forget_outcome(const protocol::Result& result, const std::string& identity_path);

}  // namespace fts::client
