// What the fleet (Agones, /metrics) needs to know of the server, taken once per tick by
// the tick loop. Today one match: rooms is 1 while it has a connected player; with rooms
// (issue 13) observe() counts the live rooms instead — the one place to change.
#pragma once

#include <cstdint>
#include <set>
#include <string>

namespace fts::server {

class GameHost;

struct FleetState {
  std::uint32_t rooms = 0;          // live rooms (matches with a connected player)
  std::set<std::string> players;    // names of the connected players (an Agones List)
  std::string phase = "lobby";      // lobby, playing, shop, game_over; "draining" while draining
  bool draining = false;            // no new players or rooms; Shutdown when rooms reach 0

  bool operator==(const FleetState&) const = default;
};

FleetState observe(const GameHost& host);

}  // namespace fts::server
