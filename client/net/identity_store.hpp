// The player's identity file (issue 41, PROTOCOL.md 5.8): an Ed25519 key made on the
// first run and kept like an ssh key, $XDG_STATE_HOME/fear-the-sphere/identity by default
// (0600 in a 0700 directory). A file that others may read is refused, as ssh refuses an
// unprotected private key.
#pragma once

#include <optional>
#include <string>

#include "fts/protocol/identity.hpp"

namespace fts::client {

// The default identity file under a state directory (state_dir()); "" for "".
std::string default_identity_path(const std::string& state_dir);

// The identity in `path`, made (and saved) when the file does not exist. nullopt with
// `why` when it cannot be read, is not an identity, is open to others, or cannot be made.
std::optional<protocol::Identity> load_or_create_identity(const std::string& path, std::string& why);

}  // namespace fts::client
