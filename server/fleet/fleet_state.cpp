#include "fleet/fleet_state.hpp"

#include "app/game_host.hpp"

namespace fts::server {

FleetState observe(const GameHost& host) {
  FleetState s;
  for (const auto& session : host.endpoint().sessions())
    if (session.connected) s.players.insert(session.name);
  s.rooms = static_cast<std::uint32_t>(host.room_ids().size());
  s.draining = host.draining();
  s.phase = s.draining ? "draining" : std::string(sim::to_string(host.match().phase));
  return s;
}

}  // namespace fts::server
