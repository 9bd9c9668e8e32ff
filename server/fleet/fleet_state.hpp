// What the fleet (Agones, /metrics) needs to know of the server, taken once per tick by
// the tick loop: the live rooms and their codes, the seats taken, the connected players'
// names, the first room's phase and whether the server drains.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace fts::server {

class GameHost;

struct FleetState {
  std::uint32_t rooms = 0;                // open rooms
  std::uint32_t seats = 0;                // seats taken in all rooms (spectators take none)
  std::vector<std::string> room_codes;    // the open rooms' codes, private ones too, in room-id order
  std::set<std::string> players;          // names of the connected players (an Agones List)
  std::string phase = "lobby";            // lobby, playing, shop, game_over; "draining" while draining
  bool draining = false;                  // no new players or rooms; Shutdown when rooms reach 0

  bool operator==(const FleetState&) const = default;
};

FleetState observe(const GameHost& host);

}  // namespace fts::server
