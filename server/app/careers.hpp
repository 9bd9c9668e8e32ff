// A room's players' careers in the running match (issue 41): what each player with an
// identity (PROTOCOL.md 5.8) did in it — the highest level reached, the most coins held,
// enemies knocked off, lives lost, time played — and its result once the player's match
// ends: out of lives or the match's game over (game_over), its session released after it
// left (quit), or the room closing (closed). Each player's match has a random key made
// when it starts, so a result written twice (a resumed room, a spool replayed) counts once
// (profiles::Store::write). Guests are not followed. Pure: the room feeds it each step's
// events and state; tests step it by hand.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fts/sim/match.hpp"
#include "profiles/store.hpp"

namespace fts::server {

struct Tally {
  std::string identity;  // fingerprint
  std::string name;
  std::string key;       // this player's match: 32 random hex digits
  std::int64_t match = 0;  // MatchState::matches_started when it began
  std::int64_t level = 0, coins = 0, knocks = 0, lives_lost = 0, play_ticks = 0;
  bool done = false;     // its result was made
  bool operator==(const Tally&) const = default;
};

class Careers {
 public:
  // The player's identity and the name it shows ("" identity: a guest, not followed).
  void identify(std::uint32_t player, const std::string& identity, const std::string& name);
  // One step: its events, then the state after it. Results of the players whose match
  // ended in it. `changed` gets the players whose tally changed (to journal).
  std::vector<profiles::MatchResult> step(const sim::MatchState& m, const std::vector<sim::Event>& events,
                                          std::int64_t unix_s, std::vector<std::uint32_t>* changed = nullptr);
  // The player's session was released (it left for good): its result (quit), if it has
  // one running.
  std::optional<profiles::MatchResult> released(std::uint32_t player, double tick_hz, std::int64_t unix_s);
  // The identity's profile is being erased (PROTOCOL.md 4.7c): its players are not
  // followed any more, and no result of their running matches is made.
  void forget(const std::string& identity);
  // The room closes: every running result (closed).
  std::vector<profiles::MatchResult> close(double tick_hz, std::int64_t unix_s);

  // The journal's form of a player's tally ("" none) and back (a resumed room).
  std::string saved(std::uint32_t player) const;
  void restore(std::uint32_t player, const std::string& identity, const std::string& saved);
  const Tally* tally(std::uint32_t player) const;

  // The random key source (tests fix it).
  std::function<std::string()> new_key;

 private:
  profiles::MatchResult finish(Tally& t, profiles::Ending ending, double tick_hz, std::int64_t unix_s);
  std::map<std::uint32_t, Tally> tallies_;
  std::map<std::uint32_t, std::pair<std::string, std::string>> who_;  // identity, name
};

}  // namespace fts::server
