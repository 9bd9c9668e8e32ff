// What the fleet (Agones, /metrics) needs to know of the server, taken once per tick by
// the tick loop: the live rooms, the connected players' names, the first room's phase
// and whether the server drains.
#pragma once

#include <cstdint>
#include <set>
#include <string>

namespace fts::server {

class GameHost;

struct FleetState {
  std::uint32_t rooms = 0;          // open rooms
  std::set<std::string> players;    // names of the connected players (an Agones List)
  std::string phase = "lobby";      // lobby, playing, shop, game_over; "draining" while draining
  bool draining = false;            // no new players or rooms; Shutdown when rooms reach 0

  bool operator==(const FleetState&) const = default;
};

FleetState observe(const GameHost& host);

}  // namespace fts::server
