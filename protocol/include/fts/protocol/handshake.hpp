// The server's handshake (issue 39, PROTOCOL.md 5): what a hello must prove before the
// endpoint gives it a session, knowing nothing of the sessions: the address it came from
// (the stateless cookie of a challenge), a name a person may read, the session's keys
// (5.7), the player's identity (5.8) and the token it brings back (sealed). The endpoint
// (server_handshake.cpp) then takes a player back or admits a new one.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include "fts/protocol/cookie.hpp"
#include "fts/protocol/identity.hpp"
#include "fts/protocol/limits.hpp"
#include "fts/protocol/messages.hpp"
#include "fts/protocol/reject.hpp"
#include "fts/protocol/seal.hpp"
#include "fts/protocol/server_session.hpp"

namespace fts::protocol {

// A hello that goes no further: what to count (none for a first hello, which is only
// challenged) and what to answer unconnected (none: dropped without a word, as a forged
// cookie is).
struct HelloAnswer {
  std::optional<Reject> counted;
  std::optional<Message> reply;
};

// What a hello proved.
struct ProvenHello {
  SessionKeys keys;
  std::string identity;  // the proven identity's fingerprint; "" a guest
  std::string token;     // "" none; "-" one that did not open (it takes nobody back)
};

class Handshake {
 public:
  Handshake(const ServerKey& key, std::uint64_t cookie_lifetime_ms);

  // Step 1, before any session is looked at: a hello without a cookie is challenged,
  // one with an expired cookie challenged again, a forged one dropped; then its name.
  // nullopt: go on.
  std::optional<HelloAnswer> screen(const Address& from, const Hello& hello, std::uint64_t now_ms) const;
  // Step 2: the keys, the identity's proof and the token. A hello with a token spends
  // one of its host's reconnects (AddressLimits::Host::takeovers) first.
  std::variant<ProvenHello, HelloAnswer> prove(const Address& from, const Hello& hello, AddressLimits& limits,
                                               std::uint64_t now_ms) const;

 private:
  ServerKey key_;
  std::uint64_t cookie_lifetime_ms_;
  KxKeyPair kx_;        // derived from the key: its public half goes in challenges
  std::string kx_hex_;  // that public key in hex
  Challenge challenge(const Address& from, std::uint64_t now_ms) const;
};

}  // namespace fts::protocol
